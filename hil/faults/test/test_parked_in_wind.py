"""The parked glider in a wind past its limit, before the launch: held as a crew holds one."""
from stack_testing.fault_flight import fly


def test_a_glider_parked_in_a_wind_past_its_limit_is_held_until_its_airborne_start():
    """Campaign seed 24, flights 83, 104 and 136: parked in 9.8 to 10.9 m/s (limits.yaml allows
    9.1), the simulator's unheld glider dropped its nose to -20 deg and crashed 0.6 s after
    power-up, before any launch, so the fault under test never took effect. The HiL now holds the
    parked glider (hil/fdm: reset_on_ground(held=True)) until the airborne start."""
    s = fly("none", flight_s=8.0, seed=100040701, extra=["--wind-mps", "10.75", "--wind-from-deg", "339.3"])
    assert not s["verdict"]["aircraft_crashed"], s["_replay"]
    assert any("airborne start" in e["event"] for e in s["events"]), s["_replay"]
