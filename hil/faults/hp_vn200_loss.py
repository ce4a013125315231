"""VN-200 link loss on the HP side: no packet reaches the HP's port (the vn200 node's serial
line) for the window. Took effect when packets were withheld and the vn200 node published none
of them. A takeover is due with the first command the HP put on the wire reporting its sensor
links down (the HP's controller is the one to notice; an HP that flies on without its INS and
says nothing shows as takeover never due and, if it strays, as the truth leaving S_x)."""
from hil.faults.base import Fault


class HpVn200Loss(Fault):
    def __init__(self, *a):
        super().__init__(*a)
        self.withheld_steps = 0
        self.published_during = None
        self.start_count = None

    def hp_vn_ok(self, t_s):
        if self.active(t_s):
            if self.start_count is None:
                self.start_count = self.ctx.waiter.count("vn")
                self.note(t_s, "HP VN-200 port silent")
            self.withheld_steps += 1
            return False
        if self.start_count is not None and self.published_during is None:
            self.published_during = self.ctx.waiter.count("vn") - self.start_count
            self.note(t_s, "HP VN-200 port back")
        return True

    def command(self, t_s, msg):
        if msg is not None and self.due_s is None and self.start_count is not None and not msg.sensor_links_healthy:
            self.due_s = t_s
            self.note(t_s, "the HP's command reports its sensor links down (seq %d)" % msg.seq)
        return super().command(t_s, msg)

    def effect(self):
        pub = self.published_during if self.published_during is not None else (
            None if self.start_count is None else self.ctx.waiter.count("vn") - self.start_count)
        if not self.withheld_steps or pub is None or pub != 0:
            return False, "withheld for %d steps; the vn200 node published %s packets meanwhile" % (self.withheld_steps, pub)
        return True, "no packet for %d HA periods; the vn200 node published none; %s" % (
            self.withheld_steps, "; ".join(self.notes))


def inject(ctx, at_s, duration_s, params):
    return HpVn200Loss(ctx, at_s, duration_s, params)
