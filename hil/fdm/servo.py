"""Servo model: a transport delay, then travel and rate limits, stepped at the simulation rate.

Kept in Python rather than in JSBSim's actuators so a trimmed start can put every servo exactly
at its trim position (JSBSim's actuators always start from zero)."""
from collections import deque


class Servo:
    def __init__(self, lo, hi, rate_per_s, delay_steps, dt_s):
        if not lo < hi:
            raise ValueError(f"servo travel [{lo}, {hi}] is empty")
        self.lo = lo
        self.hi = hi
        self.max_step = rate_per_s * dt_s
        self.delay_steps = delay_steps
        self.reset(0.0)

    def reset(self, position):
        """Servo at rest at position, every command in the delay line equal to it."""
        p = min(max(position, self.lo), self.hi)
        self.position = p
        self.command = p
        self.line = deque([p] * self.delay_steps)

    def step(self):
        """One time step: the command issued delay_steps ago moves the servo at most its rate."""
        if self.delay_steps:
            self.line.append(self.command)
            target = self.line.popleft()
        else:
            target = self.command
        delta = target - self.position
        if delta > self.max_step:
            delta = self.max_step
        elif delta < -self.max_step:
            delta = -self.max_step
        self.position += delta
        return self.position

    def set_command(self, value):
        self.command = min(max(float(value), self.lo), self.hi)
