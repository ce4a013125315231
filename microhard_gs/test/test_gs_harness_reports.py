"""The ground-station harness, when microhard_gs cannot come up, says why at once: which process
ended and its last log lines, instead of a bare timeout. A CI run once lost a whole module to
"never connected" with nothing else to read."""
import pytest

from stack_testing import gs_harness as gh


def test_a_launch_that_ends_is_reported_with_its_own_words():
    with pytest.raises(RuntimeError) as failure:
        gh.GsSystem(launch_args={"aircraft": "NoSuchAircraft"})
    report = str(failure.value)
    assert "roslaunch ended with" in report
    assert "probe running" in report
    assert "NoSuchAircraft" in report  # roslaunch's own error, from the log's last lines
