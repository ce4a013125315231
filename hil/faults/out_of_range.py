"""A surface beyond its actuator limit (outside S_u), finite and with a valid CRC (params: surface,
default elevator; value, default 1.5 x the limit in limits.yaml, in deg or throttle fraction)."""
from hil.faults.base import SURFACES, CommandFault, set_surface


class OutOfRange(CommandFault):
    def corrupt(self, t_s, m):
        surface = self.param("surface", "elevator")
        if surface not in SURFACES:
            raise ValueError("out_of_range: surface must be one of %s" % ", ".join(SURFACES))
        a = self.ctx.limits["actuators"]
        limit = a["throttle_max"] if surface == "throttle" else a[surface + "_limit_deg"]
        set_surface(m, surface, float(self.params.get("value", 1.5 * limit)))
        return m


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_PARAMS = {"surface": SURFACES}


def inject(ctx, at_s, duration_s, params):
    return OutOfRange(ctx, at_s, duration_s, params)
