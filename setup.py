"""The stack's Python packages, for catkin_python_setup() in CMakeLists.txt (not for pip).

Sourcing the workspace's setup.bash puts them on PYTHONPATH: the devel space relays each package
to its folder in the source tree, the install space holds a copy in lib/python3/dist-packages.
The nodes' scripts, the tests and the benchmarks import them by name, never by sys.path edits
(test/test_python_packages.py)."""
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(
    packages=[
        "stack_tools",
        "hil", "hil.campaigns", "hil.faults", "hil.fdm",
        "report_core",
        "stack_common",
        "stack_testing",
        "supervisor_core",
        "vn200_sim",
    ],
    package_dir={
        "stack_tools": "tools/stack_tools",
        "hil": "hil",
        "report_core": "drone_ros/report/src/report_core",
        "stack_common": "common/python/stack_common",
        "stack_testing": "test/stack_testing",
        "supervisor_core": "drone_ros/supervisor/src/supervisor_core",
        "vn200_sim": "vn200_driver/src/vn200_sim",
    },
))
