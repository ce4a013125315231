"""HaAircraftConfig is written from one table (tools/stack_tools/ha_config_schema.py): the header
arduino-cli compiles is that table's, and the generator refuses values that are not exactly its
fields, so a limit added on one side only never reaches the core as a silent zero."""
import os
import re
import subprocess
import sys

import pytest

from stack_tools import check_config, gen_aircraft_config
from stack_tools.paths import ROOT

CHECKED_IN = os.path.join(ROOT, "arduino_ha", "src", "generated", "ha_config.h")


def dg808_values():
    aircraft = os.path.join(ROOT, "aircraft", "DG808")
    return gen_aircraft_config.build(check_config.load(os.path.join(aircraft, "limits.yaml"), "limits"),
                                     check_config.load(os.path.join(aircraft, "airframe.yaml"), "airframe"))


def test_the_checked_in_struct_is_the_one_the_table_writes(tmp_path):
    fresh = tmp_path / "ha_config.h"
    subprocess.run([sys.executable, os.path.join(ROOT, "tools", "gen_aircraft_config.py"), "--types",
                    str(fresh)], check=True)
    with open(CHECKED_IN) as f:
        assert f.read() == fresh.read_text(), \
            "run `python3 tools/gen_aircraft_config.py --types arduino_ha/src/generated/ha_config.h`"


def test_the_struct_declares_every_value_the_generator_writes():
    header = open(CHECKED_IN).read()
    for key in dg808_values():
        assert re.search(r"[ *]%s[;\[]" % key, header), key


@pytest.mark.parametrize("change, named", [
    (lambda c: c.pop("stall_alpha_deg"), "no value for ['stall_alpha_deg']"),
    (lambda c: c.update(gust_margin=1.5), "no field for ['gust_margin']"),
    (lambda c: c.update(period_us=0.01), "wrong type for ['period_us']"),
])
def test_a_value_without_its_field_or_a_field_without_its_value_is_refused_by_name(change, named):
    values = dg808_values()
    change(values)
    with pytest.raises(gen_aircraft_config.ConfigError) as err:
        gen_aircraft_config.render(values, "aircraft/DG808/limits.yaml")
    assert named in str(err.value)
