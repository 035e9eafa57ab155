"""The tutorial's node: publishes its `velocity` parameter as linear.x on cmd_vel."""

import time

from geometry_msgs.msg import Twist
from rcl_interfaces.msg import ParameterDescriptor
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node


class VelParam(Node):
    """Read the `velocity` parameter every 0.1 s and publish it on cmd_vel."""

    def __init__(self):
        super().__init__('param_vel_node')
        self.timer = self.create_timer(0.1, self.timer_callback)
        self.publisher = self.create_publisher(Twist, 'cmd_vel', 10)
        self.msg = Twist()
        param_descriptor = ParameterDescriptor(
            description='Sets the velocity (in m/s) of the robot.')
        self.declare_parameter('velocity', 0.0, param_descriptor)
        # self.add_on_set_parameters_callback(self.parameter_callback)

    def timer_callback(self):
        my_param = self.get_parameter('velocity').value
        self.get_logger().info('Velocity parameter is: %f' % my_param)
        self.msg.linear.x = my_param
        self.publisher.publish(self.msg)


def _shut_down_by_ctrl_c():
    """Return True once Ctrl-C has shut rclpy down (its signal thread may lag a moment)."""
    deadline = time.monotonic() + 1.0
    while rclpy.ok() and time.monotonic() < deadline:
        time.sleep(0.01)
    return not rclpy.ok()


def main(args=None):
    rclpy.init(args=args)
    node = VelParam()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    except Exception as error:
        if not _shut_down_by_ctrl_c():
            raise
        # Ctrl-C: rclpy's signal thread shut the context down under a running callback
        node.get_logger().debug(f'Ctrl-C ended a running callback: {error!r}')
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == '__main__':
    main()
