"""A fault class is its module: hil/faults/<class>.py holds the injector and what a campaign draws
for it (CAMPAIGN_PARAMS or draw_params, CAMPAIGN_DURATION), and CLASSES names it once. Every module
that injects is a class, every class has a module and a row in hil/faults/README.md, and each
module's campaign metadata is of the form hil/campaigns/plan.py draws from."""
import os
import random
import re

import pytest

from hil import faults
from hil.campaigns import plan

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HELPERS = {"__init__", "base", "steer"}  # shared code, not classes


def test_every_injecting_module_is_a_class_and_every_class_a_module():
    modules = {f[:-3] for f in os.listdir(HERE) if f.endswith(".py")} - HELPERS
    assert modules == set(faults.CLASSES)
    assert len(faults.CLASSES) == len(set(faults.CLASSES))
    assert all(callable(faults.module(c).inject) for c in faults.CLASSES)


def test_the_readme_table_names_each_class_once():
    with open(os.path.join(HERE, "README.md"), encoding="utf-8") as f:
        first_cells = [line.split("|")[1] for line in f if line.startswith("| `")]
    named = [n for cell in first_cells for n in re.findall(r"`([a-z0-9_]+)`", cell)]
    assert sorted(named) == sorted(faults.CLASSES)


@pytest.mark.parametrize("name", faults.CLASSES)
def test_each_class_says_what_a_campaign_draws_in_a_form_the_plan_takes(name):
    mod = faults.module(name)
    assert getattr(mod, "CAMPAIGN_DURATION", "window") in ("window", "long", "none")
    space = getattr(mod, "CAMPAIGN_PARAMS", {})
    for key, values in space.items():
        assert isinstance(key, str) and values, (key, values)
        if values[0] == "u":
            assert len(values) == 3 and values[1] <= values[2], (key, values)
    assert not (space and callable(getattr(mod, "draw_params", None))), "one source of parameters"
    params = dict(plan._class_params(name, random.Random(1)))
    assert set(params) >= set(space)


def test_the_plan_takes_durations_from_the_modules():
    rng = random.Random(2)
    assert plan._duration("crash", rng, (0.5, 6.0)) == -1.0            # "none"
    assert 8.0 <= plan._duration("climb", rng, (0.5, 6.0)) <= 20.0      # "long"
    windowed = [plan._duration("nan", rng, (0.5, 6.0)) for _ in range(200)]
    assert any(d == -1.0 for d in windowed) and all(d == -1.0 or 0.5 <= d <= 6.0 for d in windowed)
    # A class no module has (a test's fake) flies with no parameters in the campaign's window.
    assert plan._class_params("quick", rng) == ()
