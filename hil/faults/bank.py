"""An HP that banks past the roll limit: aileron loop to roll_deg (default 80 deg, beyond
limits.yaml's roll_limit_deg), every command valid."""
from hil.faults.steer import SteeringFault


class Bank(SteeringFault):
    TARGET_ROLL_DEG = 80.0
    EXTREME = ("max |roll| %.1f deg", max, lambda m: abs(m.roll_deg))


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_DURATION = "long"


def inject(ctx, at_s, duration_s, params):
    return Bank(ctx, at_s, duration_s, params)
