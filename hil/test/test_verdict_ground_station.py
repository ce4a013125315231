"""What the ground station showed, held against the truth (verdicts.ground_station_view): each
GLOBAL_POSITION_INT against the nearest true position of the seconds before it arrived. A
position measured while parked that arrives after the airborne start (a loaded machine: CI saw a
197.9 ft "height error" this way) is the ground's; a frame mix-up in flight still shows."""
from types import SimpleNamespace

from stack_common import geo
from stack_common.units import FT_PER_M

from hil import verdicts
from hil.flight_record import FlightRecord
from hil.gs_monitor import Position

HOME = (40.4237054, -86.9211946, 185.25)
AIRBORNE_S, HEIGHT_FT, SPEED_FTPS = 2.0, 200.0, 60.0


def truth_at(t_s):
    """Parked at home, then launched 200 ft up flying north at 60 ft/s."""
    if t_s < AIRBORNE_S:
        return SimpleNamespace(north_ft=0.0, east_ft=0.0, height_above_home_ft=0.0, on_ground=True)
    return SimpleNamespace(north_ft=SPEED_FTPS * (t_s - AIRBORNE_S), east_ft=0.0,
                           height_above_home_ft=HEIGHT_FT, on_ground=False)


def position(arrived_s, measured_s, extra_height_ft=0.0):
    """What the ground station received at arrived_s: the position the vehicle had at measured_s."""
    tr = truth_at(measured_s)
    lat, lon, _ = geo.Ref(*HOME).from_neu_m(tr.north_ft / FT_PER_M, tr.east_ft / FT_PER_M)
    return Position(arrived_s, lat, lon, (tr.height_above_home_ft + extra_height_ft) / FT_PER_M)


def flight_with(positions):
    """A flight's record as the ground-station verdict reads it: the truth each period, what the
    ground station was shown."""
    periods = [SimpleNamespace(t_s=k * 0.01, truth=truth_at(k * 0.01)) for k in range(1001)]
    return FlightRecord(aircraft="DG808", seed=1, mode="lockstep", rate_hz=100.0, period_us=10000,
                        controller_dt_s=0.01, periods=periods, ha_periods=[], ground_s=AIRBORNE_S,
                        regions=None, stall_alphas_deg=(8.85, -8.0), plan=None, home=HOME, reach_ft=80.0,
                        gs_positions=positions)


def test_a_flight_nobody_watched_has_no_ground_station_view():
    assert verdicts.ground_station_view(flight_with(None)) is None


def test_a_parked_position_that_arrives_after_the_airborne_start_is_not_one_in_flight():
    flown = [position(t, t - 0.3) for t in (3.0, 4.0, 5.0)]
    view = verdicts.ground_station_view(flight_with([position(2.4, 1.9)] + flown))
    assert view["positions_received"] == 4
    assert view["positions_in_flight"] == 3
    assert view["max_height_error_ft"] < 0.01, view
    assert view["max_horizontal_error_ft"] < 0.5, view


def test_an_absolute_altitude_shown_as_relative_in_flight_is_still_an_error():
    field_elevation_ft = 853.0
    view = verdicts.ground_station_view(flight_with([position(5.0, 4.7, extra_height_ft=field_elevation_ft)]))
    assert view["positions_in_flight"] == 1
    assert abs(view["max_height_error_ft"] - field_elevation_ft) < 0.01, view


def test_a_position_off_track_in_flight_is_measured_against_the_nearest_true_one():
    lat, lon = position(5.0, 4.7).lat_deg, position(5.0, 4.7).lon_deg + 0.0003  # about 83 ft east
    view = verdicts.ground_station_view(flight_with([Position(5.0, lat, lon, HEIGHT_FT / FT_PER_M)]))
    assert view["positions_in_flight"] == 1
    assert 70.0 < view["max_horizontal_error_ft"] < 100.0, view
