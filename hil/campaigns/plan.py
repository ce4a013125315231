"""A campaign's flights, drawn from one campaign seed: the fault class of each (the classes dealt
round-robin in a seeded order, so every class gets its share), the flight's own seed, when the
fault starts, how long it lasts and its parameters. The same campaign seed, flight count, classes
and flight length give the same plan, and each flight's command line reproduces that flight.

The classes come from the faults package (hil/faults), each class's parameter space and duration
from its own module (CAMPAIGN_PARAMS, CAMPAIGN_DURATION, or draw_params). Every flight, of every
class, also draws its own wind (draw_wind: any direction, up to 1.5 x sensors.max_wind_ftps, light
or moderate turbulence on some) when run_flight.py takes --wind-mps, --wind-from-deg and
--turbulence."""
import dataclasses
import json
import os
import random
import shlex
import subprocess
import sys

import yaml

from hil import faults
from stack_tools.paths import ROOT  # noqa: E402  (aircraft/ of the source tree or the install)

HIL = os.path.join(ROOT, "hil")
RUN_FLIGHT = os.path.join(HIL, "run_flight.py")


@dataclasses.dataclass(frozen=True)
class Flight:
    flight_id: int
    fault_class: str
    seed: int
    fault_at_s: float
    fault_duration_s: float  # < 0: the fault never ends by itself
    params: tuple            # ((key, value), ...) as strings, sorted by key
    duration_s: float
    # The flight's own wind (run_flight.py's --wind-mps, --wind-from-deg, --turbulence): steady
    # from anywhere, up to 1.5 x sensors.max_wind_ftps, with turbulence; calm when this
    # checkout's run_flight.py takes no wind (Interface.has_wind).
    wind_mps: float = 0.0
    wind_from_deg: float = 0.0
    turbulence: str = "none"
    # The HA in the loop (run_flight.py's --ha): its host build, or its Cortex-M3 machine code
    # in QEMU.
    ha: str = "sil"
    # aircraft/<name>/ flown (run_flight.py's --aircraft): the build's (make campaign AIRCRAFT=).
    aircraft: str = "DG808"

    def params_dict(self):
        return dict(self.params)


@dataclasses.dataclass(frozen=True)
class Interface:
    """What this checkout's run_flight.py takes: the agreed fault interface (--fault-at,
    --fault-duration, --fault-param) or only the first one (--crash-at)."""
    classes: tuple
    fault_at_flag: str          # --fault-at or --crash-at
    has_duration: bool
    has_params: bool
    has_wind: bool = False      # --wind-mps, --wind-from-deg, --turbulence
    has_master: bool = False    # --master: the flights fly on their worker's kept ROS master


def _help_text(run_flight):
    r = subprocess.run([sys.executable, run_flight, "--help"], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, timeout=120)
    return r.stdout.decode(errors="replace")


def discover(run_flight=RUN_FLIGHT):
    """This checkout's interface: the fault classes of hil.faults (each module holds its own
    campaign metadata, CAMPAIGN_PARAMS and CAMPAIGN_DURATION), the flags from run_flight.py's help."""
    text = _help_text(run_flight)
    return Interface(classes=tuple(sorted(faults.CLASSES)),
                     fault_at_flag="--fault-at" if "--fault-at" in text else "--crash-at",
                     has_duration="--fault-duration" in text,
                     has_params="--fault-param" in text,
                     has_master="--master" in text,
                     has_wind=all(f in text for f in ("--wind-mps", "--wind-from-deg", "--turbulence")))


def _class_module(fault_class):
    """hil.faults.<fault_class>, or None for a class the package does not have (a test's fake)."""
    try:
        return faults.module(fault_class)
    except ValueError:
        return None


def _class_params(fault_class, rng):
    """The flight's parameters for its class, sorted (key, value) string pairs: the class
    module's own draw_params(rng) when it has one, else a draw from its CAMPAIGN_PARAMS, each
    parameter ("u", lo, hi): uniform, or a tuple of values: one of them. A class with neither
    flies with its injector's defaults."""
    mod = _class_module(fault_class)
    if mod is not None and callable(getattr(mod, "draw_params", None)):
        params = mod.draw_params(rng)
    else:
        params = {}
        for key, space in sorted(getattr(mod, "CAMPAIGN_PARAMS", {}).items()):
            if space and space[0] == "u":
                params[key] = round(rng.uniform(space[1], space[2]), 2)
            else:
                params[key] = rng.choice(space)
    return tuple(sorted((str(k), _fmt(v)) for k, v in (params or {}).items()))


def _duration(fault_class, rng, window):
    """How long the fault lasts, by its module's CAMPAIGN_DURATION: "none" (a crash has no
    duration), "long" (a steering fault needs time to take the aircraft anywhere: 8-20 s), else
    the campaign's window, a fifth of them never ending by themselves."""
    kind = getattr(_class_module(fault_class), "CAMPAIGN_DURATION", "window")
    if kind == "none":
        return -1.0
    if kind == "long":
        return round(rng.uniform(8.0, 20.0), 2)
    if rng.random() < 0.2:
        return -1.0  # never ends by itself (a hang never resumed, a link never back)
    return round(rng.uniform(*window), 2)


def _limits(aircraft):
    """aircraft/<aircraft>/limits.yaml, checked against its schema."""
    from stack_tools import check_config
    return check_config.load(os.path.join(ROOT, "aircraft", aircraft, "limits.yaml"))


def max_wind_ftps(aircraft):
    return float(_limits(aircraft)["sensors"]["max_wind_ftps"])


def beyond_design_wind(flight):
    """Why the flight's planned steady wind and turbulence are beyond limits.yaml's design wind
    ([]: within), as the simulator judges its world; for a flight that died or timed out before
    its summary said so. A wind fault's change is the simulator's to judge: not known here."""
    from hil.design_wind import DesignWind
    with open(os.path.join(ROOT, "aircraft", flight.aircraft, "airframe.yaml")) as f:
        airframe = yaml.safe_load(f)
    return DesignWind.load(_limits(flight.aircraft), airframe).steady(flight.wind_mps, flight.turbulence)


WIND_OVER_LIMIT = 1.5   # winds drawn up to this x sensors.max_wind_ftps: and beyond what the HA allows
# ... but below this x the stall speed: parked in a wind above its stall speed a glider is flying,
# not parked, and no launch happens in one (HiL: 13.1 m/s, the pitot above stall on the ground,
# home never latched and the mission upload was refused).
LAUNCHABLE_WIND_OF_STALL = 0.9


def wind_draw_limit_ftps(aircraft):
    """The strongest wind a campaign of the aircraft draws: WIND_OVER_LIMIT x max_wind_ftps,
    below LAUNCHABLE_WIND_OF_STALL x the stall speed."""
    limits = _limits(aircraft)
    return min(WIND_OVER_LIMIT * float(limits["sensors"]["max_wind_ftps"]),
               LAUNCHABLE_WIND_OF_STALL * float(limits["state"]["stall_speed_ftps"]))
TURBULENCE = (("none", 0.5), ("light", 0.35), ("moderate", 0.15))


def draw_wind(campaign_seed, flight_id, limit_ftps):
    """(wind_mps, wind_from_deg, turbulence) of one flight, from its own stream: calm one flight in
    eight, else uniform in speed up to limit_ftps (wind_draw_limit_ftps) and in direction,
    turbulence none, light or moderate (TURBULENCE's shares)."""
    r = random.Random("campaign:%d:flight:%d:wind" % (campaign_seed, flight_id))
    mps = 0.0 if r.random() < 0.125 else round(r.uniform(0.0, limit_ftps * 0.3048), 2)
    from_deg = round(r.uniform(0.0, 360.0), 1)
    u, turb = r.random(), "none"
    for level, share in TURBULENCE:
        if u < share:
            turb = level
            break
        u -= share
    return mps, from_deg, turb


def _fmt(v):
    if isinstance(v, float):
        return "%.6g" % v
    return str(v)


def make_plan(flights, seed, classes, duration_s=45.0, fault_window_s=(8.0, 20.0),
              fault_duration_s=(0.5, 6.0), interface=None, wind=True, ha="sil", aircraft="DG808"):
    """flights: how many; seed: the campaign seed; classes: the fault classes to deal from.
    A fault starts in fault_window_s (after the HP has taken control, leaving time for the
    recovery) on the HA's 10 ms grid; a fault lasts fault_duration_s (steering faults 8-20 s; a
    fifth of the others never end by themselves; a crash has no duration)."""
    if flights < 1:
        raise ValueError("a campaign needs at least one flight")
    if not classes:
        raise ValueError("a campaign needs at least one fault class")
    rng = random.Random("campaign:%d" % seed)
    order = list(classes)
    rng.shuffle(order)
    has_duration = interface is None or interface.has_duration
    has_params = interface is None or interface.has_params
    # Wind per flight, every class, when run_flight.py can fly it (else every flight is calm).
    windy = wind and (interface is None or interface.has_wind)
    limit_ftps = wind_draw_limit_ftps(aircraft) if windy else None
    plan = []
    for i in range(flights):
        cls = order[i % len(order)]
        # Each flight draws from its own stream, so flight i is the same whatever N is.
        frng = random.Random("campaign:%d:flight:%d" % (seed, i))
        at = round(frng.uniform(*fault_window_s), 2)
        dur = _duration(cls, frng, fault_duration_s) if has_duration else -1.0
        params = _class_params(cls, frng) if has_params else ()
        fl = Flight(flight_id=i, fault_class=cls, seed=frng.randrange(1, 2 ** 31 - 1),
                    fault_at_s=at, fault_duration_s=dur, params=params, duration_s=duration_s, ha=ha,
                    aircraft=aircraft)
        if windy:
            w = draw_wind(seed, i, limit_ftps)
            fl = dataclasses.replace(fl, wind_mps=w[0], wind_from_deg=w[1], turbulence=w[2])
        plan.append(fl)
    return plan


def command(flight, folder, interface, run_flight=RUN_FLIGHT, python=None):
    """The command that flies this flight (also the replay command a report prints)."""
    argv = [python or sys.executable, run_flight, "--seed", str(flight.seed), "--fault", flight.fault_class,
            interface.fault_at_flag, "%g" % flight.fault_at_s]
    if interface.has_duration:
        argv += ["--fault-duration", "%g" % flight.fault_duration_s]
    if interface.has_params:
        for k, v in flight.params:
            argv += ["--fault-param", "%s=%s" % (k, v)]
    if getattr(interface, "has_wind", False):
        argv += ["--wind-mps", "%g" % flight.wind_mps, "--wind-from-deg", "%g" % flight.wind_from_deg,
                 "--turbulence", flight.turbulence]
    if getattr(flight, "ha", "sil") != "sil":
        argv += ["--ha", flight.ha]
    argv += ["--aircraft", flight.aircraft]
    argv += ["--duration", "%g" % flight.duration_s, "--folder", folder, "--no-bag", "--quiet"]
    return argv


def shell(argv):
    return " ".join(shlex.quote(a) for a in argv)


def to_json(plan):
    return json.dumps([dict(dataclasses.asdict(f), params=dict(f.params)) for f in plan], indent=1)
