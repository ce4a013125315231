"""An HP that flies low and slow with valid commands: wings level, a pitch loop holding
height_ft above home (default 25 ft) and a throttle loop holding the calibrated airspeed
airspeed_ftps (default 60 ft/s), both on the truth; with pass_s >= 0 it climbs back to
climb_to_ft (default 200) pass_s after it got down. With the defaults it is a low pass: nothing is
wrong, so nothing may happen (no takeover, the motor kept, the aircraft climbing away). With airspeed_ftps below the HA's stall switch speed it is a slow flight
at that height, which the HA must take over and recover from without touching the ground (slow
beats low). Issue 13's HiL stories: a stall at 60 ft, a low pass at 25 ft, airspeed hovering at
stall."""
from hil.faults.steer import SteeringFault
from stack_common.units import FT_PER_M


class LowSlow(SteeringFault):
    TARGET_ROLL_DEG = 0.0
    reached_s = None

    def corrupt(self, t_s, m):
        m = super().corrupt(t_s, m)  # wings level
        tr = self.ctx.truth_at(t_s)
        height_ft = (tr.alt_msl_m - self.ctx.home[2]) * FT_PER_M
        climb_ftps = -tr.vd_mps * FT_PER_M
        airspeed_ftps = tr.airspeed_cal_mps * FT_PER_M
        target_ft = self.param("height_ft", 25.0)
        if getattr(self, "reached_s", None) is None and abs(height_ft - target_ft) < 10.0:
            self.reached_s = t_s
            self.note(t_s, "down at %.1f ft" % height_ft)
        pass_s = self.param("pass_s", -1.0)
        if pass_s >= 0.0 and self.reached_s is not None and t_s >= self.reached_s + pass_s:
            target_ft = self.param("climb_to_ft", 200.0)  # the pass is over: climb away
        # Height to pitch with damping on the climb rate, pitch to elevator (trailing edge down
        # pitches down; q damps).
        pitch_deg = max(-10.0, min(12.0, 2.0 + 0.4 * (target_ft - height_ft) - 0.5 * climb_ftps))
        m.elevator_deg = self.clamp(0.8 * (tr.pitch_deg - pitch_deg) + 0.3 * self.deg(tr.q_rad_s), "elevator")
        m.throttle = max(0.0, min(1.0, 0.4 + 0.05 * (self.param("airspeed_ftps", 60.0) - airspeed_ftps)))
        return m

    @staticmethod
    def deg(rad):
        return rad * 57.29577951308232

    def extreme(self):
        """The lowest point after the fault began, and the throttle the HA applied there (a motor
        cut for height alone would show as 0)."""
        low = min(((p.truth.height_above_home_ft, p.t_s, p.reply.applied[3], p.airspeed_cal_ftps)
                   for p in self.ctx.records if p.t_s >= self.at_s - 1e-9),
                  default=None)
        if low is None:
            return ""
        end_ft = self.ctx.records[-1].truth.height_above_home_ft
        return "lowest %.1f ft at %.2f s, throttle applied there %.3f, calibrated airspeed %.1f ft/s; " \
               "%.1f ft at the end" % (low[0], low[1], low[2], low[3], end_ft)


def inject(ctx, at_s, duration_s, params):
    return LowSlow(ctx, at_s, duration_s, params)
