"""The ground floor as Python sees it (stack_common): the C that the Due and the HP nodes run,
bound through ctypes, agrees with the vectors the C is held to (geo_vectors.csv, also read by
test_geo_wgs84.cpp), and every Python user of a position, a CRC or a controller's name goes
through it: the HiL's verdicts, its sensor model and the flight report."""
import csv
import io
import os
import random
import subprocess
import sys
import zlib

import numpy as np
import pytest
from drone_ros.msg import DecisionStatus, OperatorCommand
from stack_common import crc, geo, units
from stack_common.native import constant

from hil import verdicts
from hil.faults.base import fields_crc32
from report_core.flight_log import ned_from_home

HERE = os.path.dirname(os.path.abspath(__file__))


def vectors():
    with open(os.path.join(HERE, "geo_vectors.csv"), encoding="utf-8") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    return {r[0]: [float(x) for x in r[1:]] for r in rows}


VECTORS = vectors()


def test_the_vectors_file_is_what_its_generator_writes():
    fresh = subprocess.run([sys.executable, os.path.join(HERE, "make_geo_vectors.py")], check=True,
                           capture_output=True, text=True).stdout
    with open(os.path.join(HERE, "geo_vectors.csv"), encoding="utf-8") as f:
        assert f.read() == fresh, "run common/test/make_geo_vectors.py > common/test/geo_vectors.csv"


@pytest.mark.parametrize("name", sorted(VECTORS))
def test_each_shared_vector_holds_through_the_binding(name):
    hlat, hlon, halt, lat, lon, alt, n, e, u = VECTORS[name]
    ref = geo.Ref(hlat, hlon, halt)
    assert ref.neu_ft(lat, lon, alt) == pytest.approx((n, e, u), abs=1e-6)
    # The verdicts (geo.north_east_ft of a home tuple) and the report place it where the C does.
    assert geo.north_east_ft((hlat, hlon, halt), lat, lon) == pytest.approx((n, e), abs=1e-6)
    rn, re_ = ned_from_home([lat, lat], [lon, lon], hlat, hlon)
    assert list(rn) == pytest.approx([n, n], abs=1e-6) and list(re_) == pytest.approx([e, e], abs=1e-6)


def test_the_antimeridian_is_crossed_the_short_way_in_every_python_user():
    east_of_it = VECTORS["antimeridian_home_west_point_east"]
    west_of_it = VECTORS["antimeridian_home_east_point_west"]
    assert 130.0 < east_of_it[7] < 150.0 and -150.0 < west_of_it[7] < -130.0
    ref = geo.Ref(-16.78, 179.9998)
    # 0.0004 deg east across the meridian is where 0.0004 deg east is anywhere else.
    assert ref.north_east_ft(-16.78, -179.9998)[1] == pytest.approx(
        geo.Ref(-16.78, 0.0).north_east_ft(-16.78, 0.0004)[1], abs=1e-6)
    # The sensor model's inverse wraps too: 140 ft east of a home on the 180th meridian's west
    # side is a longitude the VN-200 reports, in [-180, 180].
    lat, lon, _ = ref.from_neu_m(0.0, 140.0 * units.M_PER_FT)
    assert -180.0 <= lon <= -179.9997


def test_arrays_of_fixes_take_the_scalar_arithmetic():
    rng = random.Random(7)
    home = geo.Ref(38.9717, -95.2353, 250.0)
    lat = np.array([38.9717 + rng.uniform(-0.05, 0.05) for _ in range(1000)])
    lon = np.array([-95.2353 + rng.uniform(-0.05, 0.05) for _ in range(1000)])
    north, east = home.north_east_ft_arrays(lat, lon)
    assert north.shape == east.shape == (1000,)
    for i in range(0, 1000, 97):
        assert (north[i], east[i]) == home.north_east_ft(lat[i], lon[i])
    with pytest.raises(ValueError):
        home.north_east_ft_arrays([1.0, 2.0], [1.0])


@pytest.mark.parametrize("home", [(91.0, 0.0, 0.0), (0.0, 180.5, 0.0), (float("nan"), 0.0, 0.0),
                                  (0.0, 0.0, 2.0e5)])
def test_a_home_the_one_judge_refuses_is_refused_in_python_too(home):
    with pytest.raises(ValueError, match="geo_ref_init"):
        geo.Ref(*home)


def test_a_degree_is_wgs84s_published_arc():
    # One degree of latitude at 45 deg is 111,132 m, of longitude 78,847 m (NGA's table).
    north_ft, east_ft = geo.Ref(45.0, 7.0).north_east_ft(46.0, 8.0)
    assert north_ft * units.M_PER_FT == pytest.approx(111132.0, abs=1.0)
    assert east_ft * units.M_PER_FT == pytest.approx(78847.0, abs=1.0)


def test_the_crc_is_the_has_and_zlibs():
    assert crc.crc32(b"123456789") == 0xCBF43926  # CRC-32/ISO-HDLC's check value
    rng = random.Random(3)
    for n in (0, 1, 37, 38, 255):
        data = bytes(rng.randrange(256) for _ in range(n))
        assert crc.crc32(data) == zlib.crc32(data) & 0xFFFFFFFF


def test_a_message_crc_from_the_hil_is_the_has_function_over_its_fields():
    cmd = OperatorCommand(command=OperatorCommand.SELECT_HA, request_id=17)
    cmd.crc32 = fields_crc32(cmd)
    raw = io.BytesIO()
    cmd.serialize(raw)
    assert cmd.crc32 == crc.crc32(raw.getvalue()[:-4])
    cmd.request_id = 18
    assert fields_crc32(cmd) != cmd.crc32


def test_the_foot_is_the_cs():
    assert units.FT_PER_M == constant("stack_common_ft_per_m")
    assert units.G_FTPS2 == pytest.approx(32.174, abs=1e-3)


def test_controller_names_come_from_the_message():
    assert verdicts.CONTROLLERS == {0: "HP", 1: "HA", 2: "RECOVERING", 3: "HA_LATCHED", 4: "MANUAL"}
    assert verdicts.CONTROLLERS[DecisionStatus.CONTROLLER_HA_LATCHED] == "HA_LATCHED"
    assert set(verdicts.HA_SIDE) == {DecisionStatus.CONTROLLER_HA, DecisionStatus.CONTROLLER_RECOVERING,
                                     DecisionStatus.CONTROLLER_HA_LATCHED}
