"""What every fault class shares: its window, its hooks into the simulator's step loop, and its
record of what it did.

Hooks, in the order the simulator calls them each HA period (lockstep):
  on_step(t_s)            before the sensors are written (process faults, ground-station requests)
  hp_vn_ok(t_s), ha_vn_ok(t_s)
                          whether the VN-200's packets of this period reach the HP's / the HA's port
  command(t_s, msg)       relay classes only (NEEDS_RELAY): msg is the HP's /servo_op of this period
                          (None when the HP sent none); returns the commands to put on the HA's
                          link now, in order
  board(t_s, b)           the HA's board inputs of this period (a Board), returned possibly changed
  after_step(t_s, reply)  the HA's answer for the period (what it received and did)
Then, once at the end:
  effect()                (took_effect, evidence): from what reached the HA or the process table
  takeover_due_s()        when the HA had to be flying at the latest by the class's own rule
                          (None: the class itself makes no takeover due; the verdict adds the
                          truth's own: the aircraft leaving S_x, the ceiling or the stall)
"""
import io
import math
from collections import namedtuple

from stack_common import crc

Board = namedtuple("Board", "rc_pulses_us rc_valid airspeed_ftps airspeed_ok battery_v battery_ok")


def rc_trimmed(limits):
    """The pilot's receiver as the HA reads it when nobody touches the sticks: throttle low,
    aileron and rudder centred, the elevator at the transmitter's trim (the airframe's level trim,
    limits.yaml's safety_controller.elevator_trim_deg: a pilot trims the aircraft to fly hands
    off, and a centred elevator dives one whose cruise needs up elevator), PIC switch: computer."""
    rc = limits["rc"]
    low, high = int(rc["pulse_min_us"]), int(rc["pulse_max_us"])
    limit_deg = float(limits["actuators"]["elevator_limit_deg"])
    trim_deg = float(limits["safety_controller"]["elevator_trim_deg"])
    elevator_us = low + round((trim_deg + limit_deg) / (2.0 * limit_deg) * (high - low))
    middle = (low + high) // 2
    return (low + (high - low) // 10, elevator_us, middle, middle, low)


SURFACES = ("elevator", "aileron", "rudder", "throttle")


def fields_crc32(msg):
    """The crc32 a message ending in one must carry (msg/ServoCommand.msg, msg/OperatorCommand.msg):
    the HA's own ha_crc32 (stack_common.crc) over its ROS serialization less that trailing uint32,
    so the layout is the .msg's own and the function the one the HA checks it with."""
    if list(msg.__slots__[-1:]) != ["crc32"] or msg._slot_types[-1] != "uint32":
        raise ValueError("%s does not end in a uint32 crc32" % msg._type)
    raw = io.BytesIO()
    msg.serialize(raw)
    return crc.crc32(raw.getvalue()[:-4])


def copy_command(m):
    from drone_ros.msg import ServoCommand
    c = ServoCommand()
    for f in ServoCommand.__slots__:
        setattr(c, f, getattr(m, f))
    return c


def set_surface(m, surface, value):
    setattr(m, surface if surface == "throttle" else surface + "_deg", value)


def finite_command(m):
    return all(math.isfinite(v) for v in (m.throttle, m.elevator_deg, m.aileron_deg, m.rudder_deg,
                                          m.alpha_est_deg, m.beta_est_deg))


class Fault:
    NEEDS_RELAY = False
    NEEDS_LINK_RELAY = False

    def __init__(self, ctx, at_s, duration_s, params):
        self.ctx = ctx
        self.at_s = float(at_s)
        self.duration_s = float(duration_s)  # negative: to the end of the flight
        self.params = params
        self.notes = []  # what it did, in order (summary "fault.evidence")
        self.due_s = None

    @property
    def name(self):
        return type(self).__module__.rsplit(".", 1)[-1]

    def active(self, t_s):
        return t_s >= self.at_s - 1e-9 and (self.duration_s < 0.0 or t_s < self.at_s + self.duration_s - 1e-9)

    def ended(self, t_s):
        return self.duration_s >= 0.0 and t_s >= self.at_s + self.duration_s - 1e-9

    def note(self, t_s, what):
        self.notes.append("t=%.2f s: %s" % (t_s, what))
        self.ctx.event(t_s, "fault %s: %s" % (self.name, what))

    def param(self, key, default):
        v = self.params.get(key, default)
        return type(default)(v) if default is not None and not isinstance(default, str) else v

    # hooks: nothing by default
    def on_step(self, t_s):
        pass

    def hp_vn_ok(self, t_s):
        return True

    def ha_vn_ok(self, t_s):
        return True

    def command(self, t_s, msg):
        return [] if msg is None else [msg]

    def board(self, t_s, b):
        return b

    def after_step(self, t_s, reply):
        pass

    def effect(self):
        raise NotImplementedError

    def takeover_due_s(self):
        return self.due_s


class CommandFault(Fault):
    """A fault in what the HP computes: each command of the window is rewritten by corrupt() on its
    way to the HA. Took effect when the HA's link delivered a corrupted command (the HA's reply
    names its sequence number as the last received in the period it was sent for); a takeover is
    due in that period."""
    NEEDS_RELAY = True
    RESIGN = True  # the HP computed the bad value itself: its CRC covers it

    def __init__(self, *a):
        super().__init__(*a)
        self.sent = []       # (t_s, seq) corrupted commands put on the link
        self.received = []   # (t_s, seq) of those the HA reported as its last received
        self.pending = None

    def corrupt(self, t_s, msg):
        raise NotImplementedError

    def command(self, t_s, msg):
        if msg is None or not self.active(t_s):
            return [] if msg is None else [msg]
        out = self.corrupt(t_s, copy_command(msg))
        if out is None:
            return [msg]
        if self.RESIGN:
            out.crc32 = fields_crc32(out)
        if not self.sent:
            self.note(t_s, self.describe(out))
        self.sent.append((t_s, out.seq))
        self.pending = (t_s, out.seq, out)
        return [out]

    def describe(self, m):
        return "seq %d: elevator %s aileron %s rudder %s throttle %s alpha_est %s beta_est %s" % (
            m.seq, m.elevator_deg, m.aileron_deg, m.rudder_deg, m.throttle, m.alpha_est_deg, m.beta_est_deg)

    def makes_due(self, m):
        """Whether the HA must reject this command (the period it arrives is the deadline)."""
        return True

    def after_step(self, t_s, reply):
        if self.pending is not None and self.pending[0] == t_s:
            # Delivered: the link brought the HA every command relayed so far, this one last.
            if reply.commands_received >= self.ctx.relayed and reply.last_seq == (self.pending[1] & 0xFFFFFFFF):
                self.received.append(self.pending[:2])
                if len(self.received) == 1:
                    self.note(t_s, "the HA received seq %d (commands %d): controller %d, reasons %#x, S_u row %.3g" % (
                        reply.last_seq, reply.commands_received, reply.controller, reply.reasons,
                        reply.actuator_region_max))
                if self.due_s is None and self.makes_due(self.pending[2]):
                    self.due_s = t_s
            self.pending = None

    def effect(self):
        if not self.ctx.relay_verified:
            return False, "the HA's link is not fed by the relay: no corrupted command can have reached it"
        if not self.received:
            return False, "%d corrupted commands sent, none reached the HA" % len(self.sent)
        return True, "%d corrupted commands reached the HA (first seq %d at %.2f s); %s" % (
            len(self.received), self.received[0][1], self.received[0][0], "; ".join(self.notes[:3]))
