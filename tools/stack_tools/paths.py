"""ROOT: the folder laid out as the source tree (aircraft/, launch/, hil/ ...), where the Python
packages read their data from.

From the source tree or a devel space, catkin relays each package to its sources, so that is the
clone itself; an install keeps the modules in lib/python3/dist-packages and the data in
share/drone_ros, which the package path (rospack) names."""
import os

PACKAGE = "drone_ros"


def _root():
    source = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    if os.path.isfile(os.path.join(source, "package.xml")):
        return source
    import rospkg  # only an install needs the package path
    return rospkg.RosPack().get_path(PACKAGE)


ROOT = _root()
