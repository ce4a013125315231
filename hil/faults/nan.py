"""NaN in one surface of the HP's command (params: surface = elevator | aileron | rudder | throttle,
default aileron), with a valid CRC: the HP computed it. Every command of the window."""
from hil.faults.base import SURFACES, CommandFault, set_surface


class Nan(CommandFault):
    def corrupt(self, t_s, m):
        surface = self.param("surface", "aileron")
        if surface not in SURFACES:
            raise ValueError("nan: surface must be one of %s" % ", ".join(SURFACES))
        set_surface(m, surface, float("nan"))
        return m


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_PARAMS = {"surface": SURFACES}


def inject(ctx, at_s, duration_s, params):
    return Nan(ctx, at_s, duration_s, params)
