"""The ground-station tests' check of the flight plan microhard_gs publishes on /way (a helper, not
a test: pytest collects only test_*.py)."""
import pytest


def assert_plan_flies(plan, legs, tolerance_ft, height_tolerance_ft):
    """plan (the probe's /way event) holds legs, each (north, east, height) in ft from home: a
    float32 MISSION_ITEM or a waypoint file's rounded degrees move a leg by up to tolerance_ft."""
    assert plan is not None, "no flight plan on /way"
    assert plan["fp"] == len(legs)
    for i, (north, east, height) in enumerate(legs):
        assert plan["north"][i] == pytest.approx(north, abs=tolerance_ft)
        assert plan["east"][i] == pytest.approx(east, abs=tolerance_ft)
        assert plan["height"][i] == pytest.approx(height, abs=height_tolerance_ft)
