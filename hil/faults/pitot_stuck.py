"""An iced pitot: the AMS5812 holds one reading (value_ftps; default the reading at the fault)
while the aircraft's airspeed goes its own way. The HP flies on the same pitot (the HA forwards
it), so a reading stuck high makes the HP slow down (issue 22 F3: stuck at 85 ft/s, the HP flew
the aircraft down to a 35 ft/s groundspeed in still air). Takeover due when the reading can no
longer be the airspeed in any wind the HA allows (pitot_failure.impossible_reading), or stuck at
or below the stall switch speed; a stuck reading that stays plausible makes none."""
from hil.faults.pitot_failure import PitotFailure


class PitotStuck(PitotFailure):
    MODE = "stuck"


def draw_params(rng):
    """Half the flights hold the reading of the fault's moment, half stick at a value anywhere
    from a blocked-low 20 ft/s to a high 110 ft/s."""
    return {} if rng.random() < 0.5 else {"value_ftps": round(rng.uniform(20.0, 110.0), 1)}


def inject(ctx, at_s, duration_s, params):
    return PitotStuck(ctx, at_s, duration_s, params)
