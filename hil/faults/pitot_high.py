"""A pitot reading high: scale x the truth + offset_ftps (default +40 ft/s: 60 reads 100, more
than any wind the HA allows can explain), a miscalibrated probe or a leaking static line. The HP flies on the same pitot, so it slows the
aircraft towards the stall while the reading says all is well (issue 22 F3; the HA's lying check
was one-sided). Takeover due when the reading can no longer be the airspeed in any wind the HA
allows (pitot_failure.impossible_reading)."""
from hil.faults.pitot_failure import PitotFailure


class PitotHigh(PitotFailure):
    MODE = "high"


def draw_params(rng):
    """A scale of 1.15 to 1.8, or an offset of 10 to 45 ft/s."""
    if rng.random() < 0.5:
        return {"scale": round(rng.uniform(1.15, 1.8), 3)}
    return {"scale": 1.0, "offset_ftps": round(rng.uniform(10.0, 45.0), 1)}


def inject(ctx, at_s, duration_s, params):
    return PitotHigh(ctx, at_s, duration_s, params)
