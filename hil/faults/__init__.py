"""Fault injectors for HiL flights: one module per fault class, one entry point each,
`inject(ctx, at_s, duration_s, params) -> Fault`, where ctx is the running simulation
(hil/sim.py's Simulation). The simulator calls the Fault's hooks from its step loop (base.py says
which and when); every class records what it did and checks, from what reached the HA or the
process table, that it took effect: a flight whose fault never took effect ends with status
fault_not_effective. A module also says what a campaign draws for its class
(hil/campaigns/plan.py): CAMPAIGN_PARAMS (each parameter ("u", lo, hi) or a tuple of values) or
its own draw_params(rng), and CAMPAIGN_DURATION ("long" for a steering fault, "none" for one
without a duration); a new class is its module plus its name in CLASSES.

    from hil import faults
    faults.CLASSES                       # the class names, in a stable order
    faults.inject("nan", sim, 20.0, 5.0, {"surface": "aileron"})
"""
import importlib

CLASSES = ("crash", "hang", "deadline_miss", "nan", "out_of_range", "frozen", "stale_replay",
           "climb", "stall", "bank", "divergence", "hp_vn200_loss", "ha_vn200_loss", "pitot_failure",
           "rc_loss", "pic_switch", "gs_request_hp", "link_bitflip", "low_slow", "ha_reset", "cold_start",
           "wind", "accelerated_stall", "pitot_stuck", "pitot_high")


def module(name):
    if name not in CLASSES:
        raise ValueError("unknown fault class %r (one of: %s)" % (name, ", ".join(CLASSES)))
    return importlib.import_module("hil.faults." + name)


def _needs(name, what):
    from hil.faults.base import Fault
    m = module(name)
    return any(isinstance(v, type) and issubclass(v, Fault) and v.__module__ == m.__name__ and getattr(v, what)
               for v in vars(m).values())


def needs_relay(name):
    """Whether the class corrupts the HP's commands, so they must pass through the simulator."""
    return _needs(name, "NEEDS_RELAY")


def needs_link_relay(name):
    """Whether the class works on the bytes of the HP-HA link (hil/link_relay.py in the middle)."""
    return _needs(name, "NEEDS_LINK_RELAY")


def inject(name, ctx, at_s, duration_s, params):
    return module(name).inject(ctx, at_s, duration_s, dict(params or {}))


def parse_params(items):
    """["surface=aileron", "value_deg=30"] -> {"surface": "aileron", "value_deg": 30.0}"""
    out = {}
    for it in items or ():
        if "=" not in it:
            raise ValueError("fault parameter %r is not KEY=VALUE" % it)
        k, v = it.split("=", 1)
        try:
            out[k.strip()] = float(v) if v.strip().lower() not in ("nan", "inf", "-inf") else v.strip()
        except ValueError:
            out[k.strip()] = v.strip()
    return out
