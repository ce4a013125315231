"""An HP that stalls the wing in a banked turn at a speed well above the 1 g stall (issue 22 F1):
valid commands, rolling into a bank of roll_deg (default 45 deg, inside the HA's roll switch at
54) at 10 deg/s, letting the nose drop for dive_s (default 2 s: a descending turn, the speed
builds), then pulling: a loop on the truth's angle of attack whose target rises from where it
was at alpha_ramp_deg_s (default 10 deg/s) to alpha_deg (default 14 deg, past the airframe's
stall at 8.85), throttle at throttle (default 0.5). The load factor climbs to nearly 3 g and the
wing stalls at some 70 ft/s, far above the HA's 46.2 ft/s stall switch speed, with roll, pitch
and rates inside the HA's switch insets: an airspeed rule alone never sees it. Takeover due when the truth's angle of attack passes the airframe's
stall angle (airframe.yaml) while the HP flies: the HA must have the servos before the wing
stalls."""
import math

from drone_ros.msg import DecisionStatus
from hil.faults.steer import SteeringFault
from stack_common.units import FT_PER_M


class AcceleratedStall(SteeringFault):
    EXTREME = ("max alpha %.1f deg", max, lambda m: m.alpha_deg)

    def __init__(self, *a):
        super().__init__(*a)
        self.stall_alpha_deg = math.degrees(self.ctx.fdm.airframe.alpha_stall_rad)
        self.crossing = None

    def corrupt(self, t_s, m):
        tr = self.ctx.truth_at(t_s)
        if getattr(self, "start_pid", None) != self.ctx.hp_pid:  # this controller's first bad command
            self.start_pid, self.start_s = self.ctx.hp_pid, t_s
            self.roll0, self.elevator0 = tr.roll_deg, m.elevator_deg
            self.banked_s = None
            self.integral = 0.0
            self.last_s = t_s
        target_roll = self.param("roll_deg", 45.0)
        step = 10.0 * (t_s - self.start_s)
        roll = min(target_roll, self.roll0 + step) if target_roll >= self.roll0 else max(target_roll, self.roll0 - step)
        m.aileron_deg = self.clamp(1.0 * (roll - tr.roll_deg) - 0.15 * math.degrees(tr.p_rad_s), "aileron")
        if self.banked_s is None and abs(tr.roll_deg - target_roll) < 5.0:
            self.banked_s, self.alpha0 = t_s, tr.alpha_deg
            self.note(t_s, "banked %.1f deg at %.1f ft/s" % (tr.roll_deg, tr.airspeed_cal_mps * FT_PER_M))
        dt = max(0.0, t_s - self.last_s)
        self.last_s = t_s
        if self.banked_s is None:
            target_alpha = None
        else:
            pull_s = t_s - self.banked_s - self.param("dive_s", 2.0)  # the nose drops, the speed builds
            target_alpha = self.alpha0 if pull_s < 0.0 else min(
                self.param("alpha_deg", 14.0), self.alpha0 + self.param("alpha_ramp_deg_s", 10.0) * pull_s)
        if target_alpha is not None:  # elevator trailing edge up (negative) raises alpha: PI on it
            err = tr.alpha_deg - target_alpha
            self.integral = max(-15.0, min(15.0, self.integral + 2.0 * err * dt))
            m.elevator_deg = self.clamp(self.elevator0 + 1.5 * err + self.integral, "elevator")
        m.throttle = self.param("throttle", 0.5)
        return m

    def after_step(self, t_s, reply):
        super().after_step(t_s, reply)
        if not self.active(t_s) or (self.crossing is not None and self.due_s is not None):
            return
        tr = self.ctx.truth_at(t_s)
        if tr.on_ground or not tr.alpha_deg > self.stall_alpha_deg:
            return
        first = self.crossing is None
        if first:
            self.crossing = (t_s, tr.airspeed_cal_mps * FT_PER_M, -tr.accel_body_mps2[2] / 9.80665,
                             tr.roll_deg, reply.controller)
        if reply.controller == DecisionStatus.CONTROLLER_HP and self.due_s is None:  # the wing stalls with the HP flying
            self.due_s = t_s
        elif not first:
            return
        self.note(t_s, "alpha %.2f deg past the stall %.2f at %.1f ft/s calibrated, %.2f g, bank %.1f deg, "
                       "controller %d" % (tr.alpha_deg, self.stall_alpha_deg, tr.airspeed_cal_mps * FT_PER_M,
                                          -tr.accel_body_mps2[2] / 9.80665, tr.roll_deg, reply.controller))


# What a campaign draws for this class (hil/campaigns/plan.py says how).
CAMPAIGN_DURATION = "long"


def draw_params(rng):
    """Banks of 30-50 deg either way, 0-3 s of dive, pulls of 3-12 deg/s to 11-18 deg, throttle
    from idle to full."""
    return {"roll_deg": round(rng.choice((-1.0, 1.0)) * rng.uniform(30.0, 50.0), 1),
            "dive_s": round(rng.uniform(0.0, 3.0), 2), "alpha_ramp_deg_s": round(rng.uniform(3.0, 12.0), 2),
            "alpha_deg": round(rng.uniform(11.0, 18.0), 1), "throttle": round(rng.uniform(0.0, 1.0), 2)}


def inject(ctx, at_s, duration_s, params):
    return AcceleratedStall(ctx, at_s, duration_s, params)
