"""The tutorial's velocity node, grown up: ranges, a read-only parameter, an on-set callback."""

import time

from geometry_msgs.msg import Twist
from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor, SetParametersResult
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.parameter import Parameter


class DescriptorVel(Node):
    """Drive at `velocity` for `travel_time` seconds, refusing trips longer than `max_travel`."""

    def __init__(self):
        super().__init__('descriptor_vel_node')
        self.declare_parameter(
            'velocity',
            0.0,
            ParameterDescriptor(
                description='Forward speed of the robot in m/s.',
                floating_point_range=[
                    FloatingPointRange(from_value=0.0, to_value=0.26, step=0.01)
                ],
            ),
        )
        self.declare_parameter(
            'travel_time',
            0.0,
            ParameterDescriptor(
                description='Seconds to drive after velocity is set; 0.0 drives until it is 0.0.',
                floating_point_range=[FloatingPointRange(from_value=0.0, to_value=30.0, step=0.1)],
            ),
        )
        self.declare_parameter(
            'max_travel',
            1.5,
            ParameterDescriptor(
                description='Longest trip in m: the free floor in front of the robot.',
                read_only=True,
            ),
        )
        # The line the tutorial leaves commented out:
        self.add_on_set_parameters_callback(self.parameter_callback)
        self.add_post_set_parameters_callback(self.parameters_set)
        self.publisher = self.create_publisher(Twist, 'cmd_vel', 10)
        self.msg = Twist()
        self.trip_start = None
        self.trip_pending = False
        self.timer = self.create_timer(0.1, self.timer_callback)
        self.get_logger().info(
            'Ready: velocity 0.0 m/s, trips up to %.1f m' % self.get_parameter('max_travel').value
        )

    def parameter_callback(self, params):
        """Refuse a velocity and travel time whose trip would leave the free floor."""
        new = {p.name: p.value for p in params}
        velocity = new.get('velocity', self.get_parameter('velocity').value)
        travel_time = new.get('travel_time', self.get_parameter('travel_time').value)
        max_travel = self.get_parameter('max_travel').value
        trip = velocity * travel_time
        if trip > max_travel + 1e-9:
            return SetParametersResult(
                successful=False,
                reason=f'a trip of {velocity:g} m/s for {travel_time:g} s is {trip:.2f} m, '
                f'longer than max_travel ({max_travel:g} m)',
            )
        return SetParametersResult(successful=True)

    def parameters_set(self, params):
        """Start a new trip whenever velocity is set (from the next tick: on simulated time
        the clock may not have started yet, and a trip timed from 0 would end at once)."""
        for param in params:
            if param.name == 'velocity':
                self.get_logger().info('Velocity parameter is: %f' % param.value)
                self.trip_start = None
                self.trip_pending = param.value > 0.0

    def timer_callback(self):
        """Publish the velocity; end the trip once travel_time has passed."""
        velocity = self.get_parameter('velocity').value
        travel_time = self.get_parameter('travel_time').value
        if self.trip_pending:  # the trip starts with the first message that drives it
            self.trip_start, self.trip_pending = self.get_clock().now(), False
        if self.trip_start is not None and travel_time > 0.0:
            driven = (self.get_clock().now() - self.trip_start).nanoseconds * 1e-9
            if driven >= travel_time:
                self.get_logger().info('Trip of %.1f s done, stopping' % travel_time)
                self.set_parameters([Parameter('velocity', value=0.0)])
                velocity = 0.0
        self.msg.linear.x = velocity
        self.publisher.publish(self.msg)


def _shut_down_by_ctrl_c():
    """Return True once Ctrl-C has shut rclpy down (its signal thread may lag a moment)."""
    deadline = time.monotonic() + 1.0
    while rclpy.ok() and time.monotonic() < deadline:
        time.sleep(0.01)
    return not rclpy.ok()


def main(args=None):
    rclpy.init(args=args)
    node = DescriptorVel()
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
