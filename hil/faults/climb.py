"""An HP that climbs through the 400 ft ceiling: full throttle, nose held at pitch_deg (default
12 deg), every command valid."""
from hil.faults.steer import SteeringFault


class Climb(SteeringFault):
    TARGET_PITCH_DEG = 12.0
    THROTTLE = 1.0
    EXTREME = ("max height %.0f ft above home", max, lambda m: m.height_above_home_ft)


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_PARAMS = {"pitch_deg": ("u", 8.0, 15.0)}
CAMPAIGN_DURATION = "long"


def inject(ctx, at_s, duration_s, params):
    return Climb(ctx, at_s, duration_s, params)
