"""A turtle's motion as real turtlesim computes it, in the window's meters (pure)."""

import math
import struct

# The real window is 500 pixels at 45 pixels (a turtle image) per meter: (500 - 1) / 45, as
# a C++ float, on each side; turtle1 starts in its middle.
PIXELS_PER_METER = 45
WORLD_SIZE = struct.unpack('f', struct.pack('f', 499 / PIXELS_PER_METER))[0]
UPDATE_PERIOD = 0.016  # seconds: the real window's update timer, also each step's dt
COMMAND_TIMEOUT = 1.0  # seconds: a turtle stops when commands stop coming
STEP_NS = round(UPDATE_PERIOD * 1e9)
MOST_STEPS_OWED = round(COMMAND_TIMEOUT / UPDATE_PERIOD)  # a command's whole second


def steps_due(next_step, now):
    """Return the times (ns) of the steps due by `now`, from `next_step` on, and the time of
    the next one. A late timer (a busy machine) makes up what it owes, up to a command's
    second; further behind (a suspended machine) or ahead (the clock went back), the steps
    start again from `now`."""
    behind = now - next_step
    if behind >= MOST_STEPS_OWED * STEP_NS or behind < -STEP_NS:
        next_step = now
    due = []
    while next_step <= now:
        due.append(next_step)
        next_step += STEP_NS
    return due, next_step


def normalize_angle(angle):
    """Return `angle` in [-pi, pi), as turtlesim does."""
    return angle - 2 * math.pi * math.floor((angle + math.pi) / (2 * math.pi))


class Turtle:
    """One turtle's pose (x right, y up, theta counter-clockwise) and last velocity command."""

    def __init__(self, x, y, theta):
        self.x, self.y, self.theta = x, y, theta
        self.linear_x = self.linear_y = self.angular = 0.0

    def command(self, linear_x, linear_y, angular):
        """Take a velocity command (linear_y is used only by holonomic turtles)."""
        self.linear_x, self.linear_y, self.angular = linear_x, linear_y, angular

    def stop(self):
        """Drop the last command."""
        self.command(0.0, 0.0, 0.0)

    def teleport_absolute(self, x, y, theta):
        """Jump to (x, y, theta); y above the window is brought down to its top edge."""
        self.x, self.y, self.theta = x, min(y, WORLD_SIZE), theta

    def teleport_relative(self, linear, angular):
        """Turn by `angular`, then jump `linear` meters ahead."""
        self.theta += angular
        self.x += math.cos(self.theta) * linear
        self.y += math.sin(self.theta) * linear

    def step(self, dt):
        """Move for dt seconds; return the pose before clamping if the turtle hit a wall."""
        self.theta = normalize_angle(self.theta + self.angular * dt)
        cos, sin = math.cos(self.theta), math.sin(self.theta)
        self.x += (cos * self.linear_x - sin * self.linear_y) * dt
        self.y += (sin * self.linear_x + cos * self.linear_y) * dt
        outside = (self.x, self.y)
        self.x = min(max(self.x, 0.0), WORLD_SIZE)
        self.y = min(max(self.y, 0.0), WORLD_SIZE)
        return outside if outside != (self.x, self.y) else None

    @property
    def linear_velocity(self):
        """Return the speed Pose reports."""
        return math.hypot(self.linear_x, self.linear_y)
