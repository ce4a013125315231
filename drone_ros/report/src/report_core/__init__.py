"""ROS-free core of the post-flight report and the rviz markers: plain records in, figures,
HTML and marker descriptions out. The ROS edges live in ../../scripts."""
