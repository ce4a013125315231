"""Fixtures of the package-wide tests."""
import pytest
from stack_testing.ros_master import private_master


@pytest.fixture(scope="module")
def master():
    """A rosmaster of the module's own (stack_testing.ros_master): the environment to start nodes in."""
    with private_master() as env:
        yield env
