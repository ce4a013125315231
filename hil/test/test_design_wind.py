"""The DG808's design wind (limits.yaml design_wind, hil/design_wind.py): the air in which a
campaign claims the Simplex property. The HiL campaign of seed 24 drew winds no aircraft
survives with its wing unstalled; those are judged on survival, in a table of their own, and
the rest keep the whole property."""
import copy
import math
import os

import pytest
import yaml

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
from hil.campaigns import flight as flight_mod  # noqa: E402
from hil.campaigns import report as report_mod  # noqa: E402
from hil.design_wind import DesignWind, DesignWindError  # noqa: E402
from hil.faults.wind import to_vector  # noqa: E402
from hil.fdm import Wind  # noqa: E402

DG808 = os.path.join(ROOT, "aircraft", "DG808")


def docs():
    with open(os.path.join(DG808, "limits.yaml")) as f, open(os.path.join(DG808, "airframe.yaml")) as g:
        return yaml.safe_load(f), yaml.safe_load(g)


def design():
    return DesignWind.load(*docs())


def change(base, target, ramp_s, veer_deg_s=0.0):
    """base and target as (mps, from_deg)."""
    return design().change(to_vector(Wind(base[1], base[0], "none")), to_vector(Wind(target[1], target[0], "none")),
                           ramp_s, veer_deg_s, "none")


def test_the_dg808_design_wind_is_its_steady_limit_a_gust_and_a_shear_it_can_fly():
    d = design()
    assert d.steady_ftps == 30.0 and d.gust_ftps == 13.0 and d.shear_ftps2 == 5.0 and d.turbulence == "moderate"


def test_a_gust_that_leaves_the_cruise_below_the_stall_switch_speed_is_refused():
    limits, airframe = docs()
    bad = copy.deepcopy(limits)
    bad["design_wind"]["gust_ftps"] = 14.0  # 60 - 46.2 = 13.8
    with pytest.raises(DesignWindError, match="gust_ftps = 14.*46.2 ft/s stall switch speed"):
        DesignWind.load(bad, airframe)


def test_a_shear_faster_than_a_dive_at_the_pitch_limit_regains_is_refused():
    limits, airframe = docs()
    bad = copy.deepcopy(limits)
    bad["design_wind"]["shear_ftps2"] = 6.0  # g sin(10 deg) = 5.6
    with pytest.raises(DesignWindError, match="shear_ftps2 = 6.*5.6 ft/s"):
        DesignWind.load(bad, airframe)


def test_seed_24s_killer_winds_are_beyond_it():
    # #94: an 11.44 m/s headwind reversed into 12.76 m/s from behind over 3 s.
    why = change((11.44, 43.4), (12.76, 43.4 + 180.0), 3.0)
    assert any(w.startswith("steady 41.9 ft/s") for w in why), why
    assert any("a change of 79.4 ft/s in 3 s" in w for w in why), why
    # #44: 12.17 m/s from calm in 0.5 s; #119: a 9.4 m/s change in 0.5 s veering 7 deg/s.
    assert any("a change of 39.9 ft/s in 0.5 s" in w for w in change((0.0, 0.0), (12.17, 164.1), 0.5))
    why = change((3.41, 67.0), (6.32, 215.2), 0.5, veer_deg_s=-7.04)
    assert any(w.startswith("a change of 30.") for w in why) and not any(w.startswith("a veer") for w in why), why


def test_a_field_days_winds_are_within_it():
    assert change((0.0, 0.0), (3.9, 180.0), 0.0) == []       # a 12.8 ft/s gust from behind, at once
    assert change((6.0, 82.0), (9.0, 262.0), 10.0) == []     # a 15 m/s reversal over 10 s
    assert design().steady(9.1, "moderate") == []
    assert design().steady(9.2, "none") == ["steady 30.2 ft/s (design: 30)"]


def test_a_steady_veer_faster_than_the_shear_is_beyond_it():
    why = change((0.0, 0.0), (9.0, 0.0), 10.0, veer_deg_s=10.0)  # 29.5 ft/s turning 10 deg/s: 5.2 ft/s^2
    assert why == ["a veer of 5.2 ft/s^2 (design: 5)"]


def row(**kw):
    r = {c: None for c in flight_mod.COLUMNS}
    r.update(flight_id=1.0, fault_class="wind", seed=5.0, fault_at_s=10.0, status="ok", took_effect=True, ok=False,
             unsafe_commands=0.0, envelope_violations_under_ha_s=0.0, stalled_under_ha_s=1.35,
             aircraft_crashed=False, beyond_design_wind="", command="replay")
    r.update(kw)
    return r


def test_beyond_the_design_wind_a_flight_is_judged_on_survival():
    stalled = row(beyond_design_wind="a change of 79.4 ft/s in 3 s")
    assert flight_mod.broke_property(stalled) is False  # stalled 1.35 s under the HA, and flew on
    assert flight_mod.broke_property(row(beyond_design_wind="x", aircraft_crashed=True)) is True
    assert flight_mod.broke_property(row(beyond_design_wind="x", unsafe_commands=2.0)) is True
    # The same stall inside the design wind breaks the property.
    assert flight_mod.broke_property(row()) is True


def test_the_report_gives_the_beyond_flights_a_table_of_their_own(tmp_path):
    rows = [row(flight_id=float(i), ok=True, stalled_under_ha_s=0.0) for i in range(4)]
    rows.append(row(flight_id=4.0, beyond_design_wind="steady 41.9 ft/s (design: 30)"))
    rows.append(row(flight_id=5.0, beyond_design_wind="a change of 39.9 ft/s in 0.5 s", aircraft_crashed=True))
    for r in rows:
        r["broke_property"] = flight_mod.broke_property(r)
    stats, text = report_mod.write(rows, str(tmp_path))
    assert {s["class"]: s["flights"] for s in stats} == {"wind": 4, "all": 4}
    assert "beyond the design wind (2 flights; judged on survival" in text
    assert "#5 wind seed 5: crashed beyond the design wind (a change of 39.9 ft/s in 0.5 s)" in text
    assert "#4 wind" not in text
    page = (tmp_path / "report" / "report.html").read_text()
    assert "Beyond the design wind (judged on survival" in page
    assert math.isfinite(stats[0]["stalled_under_ha_s"])
