"""One turtle's ROS interfaces, as real turtlesim gives each turtle (under its name)."""

from geometry_msgs.msg import Twist
from rclpy.action import ActionServer, CancelResponse, GoalResponse
from rclpy.qos import QoSProfile, ReliabilityPolicy
from rclpy.task import Future
from turtlesim.action import RotateAbsolute
from turtlesim.msg import Color, Pose
from turtlesim.srv import SetPen, TeleportAbsolute, TeleportRelative

from .canvas import DEFAULT_PEN, DEFAULT_PEN_WIDTH
from .kinematics import COMMAND_TIMEOUT, normalize_angle, Turtle, WORLD_SIZE

TOPIC_QOS = QoSProfile(depth=7, reliability=ReliabilityPolicy.RELIABLE)
UNDRAWN = (255, 255, 255)  # the colour sensor over the background: the real one's empty image


class TurtleInterfaces:
    """cmd_vel, pose, color_sensor, set_pen, teleport_* and rotate_absolute of one turtle."""

    def __init__(self, node, name, x, y, theta, holonomic):
        self.node, self.name, self.holonomic = node, name, holonomic
        self.turtle = Turtle(x, y, theta)
        self.pen, self.pen_width, self.pen_on = DEFAULT_PEN, DEFAULT_PEN_WIDTH, True
        self.teleports = []
        self.rotation = None  # (goal handle, start heading, finished future)
        self.rotation_results = {}  # goal id -> the future its execute callback awaits
        self.last_command = node.get_clock().now()
        self.subscription = node.create_subscription(
            Twist, f'{name}/cmd_vel', self.on_command, TOPIC_QOS)
        self.services = [
            node.create_service(SetPen, f'{name}/set_pen', self.on_set_pen),
            node.create_service(
                TeleportRelative, f'{name}/teleport_relative', self.on_teleport_relative),
            node.create_service(
                TeleportAbsolute, f'{name}/teleport_absolute', self.on_teleport_absolute),
        ]
        self.pose_publisher = node.create_publisher(Pose, f'{name}/pose', TOPIC_QOS)
        self.color_publisher = node.create_publisher(Color, f'{name}/color_sensor', TOPIC_QOS)
        self.action = ActionServer(
            node, RotateAbsolute, f'{name}/rotate_absolute', self.execute_rotation,
            goal_callback=lambda _goal: GoalResponse.ACCEPT,
            cancel_callback=lambda _goal: CancelResponse.ACCEPT,
            handle_accepted_callback=self.on_rotation_accepted)

    def destroy(self):
        """Remove this turtle's topics, services and action (it was killed)."""
        self.abort_rotation()
        self.action.destroy()
        self.node.destroy_subscription(self.subscription)
        for service in self.services:
            self.node.destroy_service(service)
        self.node.destroy_publisher(self.pose_publisher)
        self.node.destroy_publisher(self.color_publisher)

    def on_command(self, msg):
        self.last_command = self.node.get_clock().now()
        side = msg.linear.y if self.holonomic() else 0.0
        self.turtle.command(msg.linear.x, side, msg.angular.z)
        if self.rotation is not None:
            self.node.get_logger().warn(
                'Velocity command received during rotation goal. Aborting goal')
            self.abort_rotation()

    def on_set_pen(self, request, response):
        self.pen_on = not request.off
        if request.off:
            return response
        self.pen = (request.r, request.g, request.b)
        if request.width != 0:
            self.pen_width = request.width
        return response

    def on_teleport_relative(self, request, response):
        self.teleports.append(('relative', request.linear, request.angular))
        return response

    def on_teleport_absolute(self, request, response):
        self.teleports.append(('absolute', request.x, request.y, request.theta))
        return response

    def on_rotation_accepted(self, goal_handle):
        if self.rotation is not None:
            self.node.get_logger().warn(
                'Rotation goal received before a previous goal finished. Aborting previous goal')
            self.abort_rotation()
        done = Future()
        self.rotation_results[bytes(goal_handle.goal_id.uuid)] = done
        self.rotation = (goal_handle, self.turtle.theta, done)
        goal_handle.execute()

    async def execute_rotation(self, goal_handle):
        """Wait for the update loop to finish the goal; return its result."""
        return await self.rotation_results.pop(bytes(goal_handle.goal_id.uuid))

    def abort_rotation(self):
        """End the current rotation goal as aborted (a velocity command, a newer goal)."""
        if self.rotation is not None:
            self._finish_rotation('abort')

    def _finish_rotation(self, outcome):
        goal_handle, start, done = self.rotation
        self.rotation = None
        result = RotateAbsolute.Result(delta=normalize_angle(start - self.turtle.theta))
        getattr(goal_handle, outcome)()
        done.set_result(result)

    def update(self, dt, canvas, at=None):
        """Teleport, rotate and move for the step due at `at` (ns of the node's clock; now if
        None), draw, publish; return True if it changed."""
        before = (self.turtle.x, self.turtle.y, self.turtle.theta)
        for request in self.teleports:
            start = (self.turtle.x, self.turtle.y)
            if request[0] == 'relative':
                self.turtle.teleport_relative(*request[1:])
            else:
                self.turtle.teleport_absolute(*request[1:])
            canvas.lift(self.name)
            self._draw(canvas, start)
            canvas.lift(self.name)
        self.teleports.clear()
        self._rotate()
        if at is None:
            at = self.node.get_clock().now().nanoseconds
        elapsed = at - self.last_command.nanoseconds
        if elapsed > COMMAND_TIMEOUT * 1e9:
            self.turtle.stop()
        start = (self.turtle.x, self.turtle.y)
        outside = self.turtle.step(dt)
        if outside is not None:
            self.node.get_logger().warn(
                f'Oh no! I hit the wall! (Clamping from [x={outside[0]:f}, '
                f'y={WORLD_SIZE - outside[1]:f}])')
        if start != (self.turtle.x, self.turtle.y):
            self._draw(canvas, start)
        self._publish(canvas)
        return before != (self.turtle.x, self.turtle.y, self.turtle.theta)

    def _draw(self, canvas, start):
        if self.pen_on:
            canvas.draw(self.name, start, (self.turtle.x, self.turtle.y), self.pen,
                        self.pen_width)
        else:
            canvas.lift(self.name)

    def _rotate(self):
        if self.rotation is None:
            return
        goal_handle = self.rotation[0]
        if goal_handle.is_cancel_requested:
            self.node.get_logger().info('Rotation goal canceled')
            self._finish_rotation('canceled')
            self.turtle.stop()
            return
        goal = normalize_angle(goal_handle.request.theta)
        remaining = normalize_angle(goal - self.turtle.theta)
        goal_handle.publish_feedback(RotateAbsolute.Feedback(remaining=remaining))
        if abs(normalize_angle(self.turtle.theta - goal)) < 0.02:
            self.node.get_logger().info('Rotation goal completed successfully')
            self._finish_rotation('succeed')
            self.turtle.stop()
        else:
            self.turtle.command(0.0, 0.0, -1.0 if remaining < 0.0 else 1.0)
            self.last_command = self.node.get_clock().now()

    def _publish(self, canvas):
        self.pose_publisher.publish(Pose(
            x=float(self.turtle.x), y=float(self.turtle.y), theta=float(self.turtle.theta),
            linear_velocity=self.turtle.linear_velocity,
            angular_velocity=float(self.turtle.angular)))
        r, g, b = canvas.colour_at(self.turtle.x, self.turtle.y) or UNDRAWN
        self.color_publisher.publish(Color(r=r, g=g, b=b))
