"""An HP that flies the aircraft into a stall: throttle closed, nose held at pitch_deg (default
20 deg) until the speed is gone, every command valid."""
from hil.faults.steer import SteeringFault


class Stall(SteeringFault):
    TARGET_PITCH_DEG = 20.0
    THROTTLE = 0.0
    EXTREME = ("min true airspeed %.1f ft/s", min, lambda m: m.airspeed_ftps)


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_DURATION = "long"


def inject(ctx, at_s, duration_s, params):
    return Stall(ctx, at_s, duration_s, params)
