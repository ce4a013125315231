"""The HP supervisor's ROS-free-of-nodes helpers: node_query (master lookup, getPid with a
deadline), shared with the HiL simulator."""
