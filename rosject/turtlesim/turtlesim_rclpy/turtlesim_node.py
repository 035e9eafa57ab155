"""turtlesim_node in rclpy: the real node's parameters, topics, services, action and log lines.

Jazzy's turtlesim is C++ with a Qt window; the course has neither. This node declares what the
real /turtlesim declares, logs what it logs and moves its turtles as the real one does. Its
window is a page in the browser (course_lib.turtlesim_view), whose address it prints first.
"""

import threading

from rcl_interfaces.msg import IntegerRange, ParameterDescriptor, ParameterEvent
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.qos import qos_profile_sensor_data, QoSProfile
from std_srvs.srv import Empty
from turtlesim.srv import Kill, Spawn

from .canvas import Canvas
from .kinematics import STEP_NS, steps_due, UPDATE_PERIOD, WORLD_SIZE
from .rclcpp_like import declare_parameter_events_qos, shut_down_by_ctrl_c
from .turtle import TurtleInterfaces
from .window import open_window, window_scene

DEFAULT_BACKGROUND = {'background_r': 0x45, 'background_g': 0x56, 'background_b': 0xFF}
CHANNELS = {'background_r': 'Red', 'background_g': 'Green', 'background_b': 'Blue'}
PARAMETER_EVENTS_QOS = QoSProfile(depth=100, reliability=qos_profile_sensor_data.reliability)


class Turtlesim(Node):
    """The /turtlesim node: the window's turtles, its services and its background."""

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
        self.lock = threading.Lock()  # the window's server reads what the update loop changes
        self.canvas = Canvas()
        self.turtles = {}
        self.id_counter = 0
        self.create_service(Empty, 'clear', self.on_clear)
        self.create_service(Empty, 'reset', self.on_reset)
        self.create_service(Spawn, 'spawn', self.on_spawn)
        self.create_service(Kill, 'kill', self.on_kill)
        # Real turtlesim redraws its window on its own parameter events; this window's page
        # draws the parameters at every refresh, so the subscription only keeps the graph real.
        self.create_subscription(
            ParameterEvent, '/parameter_events', lambda _event: None, PARAMETER_EVENTS_QOS)
        self.get_logger().info(
            f'Starting turtlesim with node name {self.get_fully_qualified_name()}')
        self.spawn_turtle('', WORLD_SIZE / 2.0, WORLD_SIZE / 2.0, 0.0)
        self.next_step = self.get_clock().now().nanoseconds + STEP_NS
        self.create_timer(UPDATE_PERIOD, self.on_update)

    def background(self):
        """Return the background colour the parameters give."""
        return tuple(self.get_parameter(name).value for name in DEFAULT_BACKGROUND)

    def spawn_turtle(self, name, x, y, theta):
        """Add a turtle (turtleN when `name` is empty); return its name, '' if it exists."""
        if not name:
            self.id_counter += 1
            name = f'turtle{self.id_counter}'
            while name in self.turtles:
                self.id_counter += 1
                name = f'turtle{self.id_counter}'
        elif name in self.turtles:
            return ''
        with self.lock:
            self.turtles[name] = TurtleInterfaces(
                self, name, x, y, theta, lambda: self.get_parameter('holonomic').value)
        self.get_logger().info(
            f'Spawning turtle [{name}] at x=[{x:f}], y=[{y:f}], theta=[{theta:f}]')
        return name

    def on_spawn(self, request, response):
        response.name = self.spawn_turtle(request.name, request.x, request.y, request.theta)
        if not response.name:
            self.get_logger().error(f'A turtle named [{request.name}] already exists')
        return response

    def on_kill(self, request, response):
        with self.lock:
            turtle = self.turtles.pop(request.name, None)
        if turtle is None:
            self.get_logger().error(
                f'Tried to kill turtle [{request.name}], which does not exist')
        else:
            turtle.destroy()
        return response

    def on_clear(self, request, response):
        self.get_logger().info('Clearing turtlesim.')
        with self.lock:
            self.canvas.clear()
        return response

    def on_reset(self, request, response):
        self.get_logger().info('Resetting turtlesim.')
        with self.lock:
            turtles, self.turtles = list(self.turtles.values()), {}
        for turtle in turtles:
            turtle.destroy()
        self.id_counter = 0
        self.spawn_turtle('', WORLD_SIZE / 2.0, WORLD_SIZE / 2.0, 0.0)
        with self.lock:
            self.canvas.clear()
        return response

    def on_update(self):
        """Step the turtles once for each step due, each at its own time (`steps_due`).

        The real window steps once per timer tick. In Python on a busy machine ticks come late
        or not at all, and a command (followed for 1 s) moved a turtle 45 steps instead of 62.
        """
        now = self.get_clock().now().nanoseconds
        with self.lock:
            due, self.next_step = steps_due(self.next_step, now)
            for at in due:
                for turtle in list(self.turtles.values()):
                    turtle.update(UPDATE_PERIOD, self.canvas, at=at)

    def scene(self):
        """Return what the window shows now (called by the window's server)."""
        with self.lock:
            return window_scene(self.background(), self.canvas, self.turtles.values())



def main(args=None):
    rclpy.init(args=args)
    window = open_window()  # its address first, as the real window shows before the node logs
    node = Turtlesim()
    if window is not None:
        window.show(node.scene, node.get_fully_qualified_name())
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    except Exception as error:
        if not shut_down_by_ctrl_c():
            raise
        # Ctrl-C: rclpy's signal thread shut the context down under a running callback
        node.get_logger().debug(f'Ctrl-C ended a running callback: {error!r}')
    finally:
        if window is not None:
            window.stop()
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == '__main__':
    main()
