"""The HiL simulator and its tools: the flight dynamics (fdm), the faults, the campaigns, the
verdicts and the sensors. A Python package (setup.py at the root, catkin_python_setup): with the
workspace's setup.bash sourced `import hil.sim` works from any folder."""
