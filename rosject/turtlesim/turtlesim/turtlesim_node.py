"""turtlesim_node in rclpy: the real node's parameters, and a turtle that /turtle1/cmd_vel moves.

Jazzy's turtlesim is C++ with a Qt window; the course has neither. This node declares what
the real /turtlesim declares (background_r/g/b with their ranges, holonomic), logs what it
logs, and moves turtle1 as the real one does. It has no window, and no /turtle1/pose: the
turtlesim messages have no wheel.
"""

import math
import struct

from geometry_msgs.msg import Twist
from rcl_interfaces.msg import IntegerRange, ParameterDescriptor
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node

from .rclcpp_like import declare_parameter_events_qos

DEFAULT_BACKGROUND = {'background_r': 0x45, 'background_g': 0x56, 'background_b': 0xFF}
CHANNELS = {'background_r': 'Red', 'background_g': 'Green', 'background_b': 'Blue'}
# The real window is 500 pixels wide at 45 pixels (a turtle image) per meter; turtle1 starts in
# its middle.
WORLD_SIZE = struct.unpack('f', struct.pack('f', 499 / 45.0))[0]  # a C++ float
UPDATE_PERIOD = 0.016  # seconds, as the real node's update timer
COMMAND_TIMEOUT = 1.0  # seconds: a turtle stops when commands stop coming, as the real one


class Turtle:
    """One turtle's pose, moved by the last velocity command (pure)."""

    def __init__(self, x, y, theta):
        self.x, self.y, self.theta = x, y, theta
        self.linear_x = self.linear_y = self.angular = 0.0

    def step(self, dt, holonomic):
        """Move for dt seconds; stay inside the world, as the real turtle does."""
        self.theta = math.atan2(
            math.sin(self.theta + self.angular * dt), math.cos(self.theta + self.angular * dt))
        cos, sin = math.cos(self.theta), math.sin(self.theta)
        side = self.linear_y if holonomic else 0.0
        self.x = min(max(self.x + (cos * self.linear_x - sin * side) * dt, 0.0), WORLD_SIZE)
        self.y = min(max(self.y + (sin * self.linear_x + cos * side) * dt, 0.0), WORLD_SIZE)


class Turtlesim(Node):
    """The /turtlesim node with turtle1."""

    def __init__(self):
        super().__init__('turtlesim')
        for name, value in DEFAULT_BACKGROUND.items():
            self.declare_parameter(name, value, ParameterDescriptor(
                description=f'{CHANNELS[name]} channel of the background color',
                integer_range=[IntegerRange(from_value=0, to_value=255, step=1)],
            ))
        self.declare_parameter('holonomic', False, ParameterDescriptor(
            description='If true, then turtles will be holonomic'))
        declare_parameter_events_qos(self)
        self.get_logger().info(
            f'Starting turtlesim with node name {self.get_fully_qualified_name()}')
        middle = WORLD_SIZE / 2.0
        self.turtle = Turtle(middle, middle, 0.0)
        self.last_command = None
        self.create_subscription(Twist, 'turtle1/cmd_vel', self.on_command, 1)
        self.create_timer(UPDATE_PERIOD, self.on_update)
        self.get_logger().info(
            f'Spawning turtle [turtle1] at x=[{middle:f}], y=[{middle:f}], theta=[{0.0:f}]')

    def on_command(self, msg):
        self.turtle.linear_x, self.turtle.linear_y = msg.linear.x, msg.linear.y
        self.turtle.angular = msg.angular.z
        self.last_command = self.get_clock().now()

    def on_update(self):
        now = self.get_clock().now()
        if self.last_command and (now - self.last_command).nanoseconds > COMMAND_TIMEOUT * 1e9:
            self.turtle.linear_x = self.turtle.linear_y = self.turtle.angular = 0.0
        self.turtle.step(UPDATE_PERIOD, self.get_parameter('holonomic').value)


def main(args=None):
    rclpy.init(args=args)
    node = Turtlesim()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == '__main__':
    main()
