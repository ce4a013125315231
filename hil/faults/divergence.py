"""Estimator divergence: the HP's alpha and beta estimates run away from its own values at
params rate_deg_s (default 20 deg/s, alpha up, beta down); its surfaces stay as computed. A
takeover is due with the first estimate beyond its limit in limits.yaml."""
from hil.faults.base import CommandFault


class Divergence(CommandFault):
    def corrupt(self, t_s, m):
        d = self.param("rate_deg_s", 20.0) * (t_s - self.at_s)
        m.alpha_est_deg += d
        m.beta_est_deg -= d
        return m

    def makes_due(self, m):
        st = self.ctx.limits["state"]
        return abs(m.alpha_est_deg) > st["alpha_limit_deg"] or abs(m.beta_est_deg) > st["beta_limit_deg"]


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_PARAMS = {"rate_deg_s": ("u", 5.0, 40.0)}
CAMPAIGN_DURATION = "long"


def inject(ctx, at_s, duration_s, params):
    return Divergence(ctx, at_s, duration_s, params)
