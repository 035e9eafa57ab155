"""One line for a program of the ROS 2 docs the course cannot run: what to use instead (pure).

The course's ROS 2 comes from Python wheels, which have no rclcpp: C++ nodes cannot run.
"""

from __future__ import annotations

__all__ = ["absent_program_hint"]

_NEEDS_RCLCPP = (
    "`ros2 run {package} {executable}` needs rclcpp (C++), which the course's ROS 2 lacks"
)
# The closest thing the course has, per (package, executable); "*" for the whole package.
_CLOSEST: dict[tuple[str, str], str] = {
    ("demo_nodes_cpp", "talker"): 'ros2 topic pub /chatter std_msgs/msg/String "{data: Hello}"',
    ("demo_nodes_cpp", "listener"): "ros2 topic echo /chatter",
    ("demo_nodes_py", "talker"): 'ros2 topic pub /chatter std_msgs/msg/String "{data: Hello}"',
    ("demo_nodes_py", "listener"): "ros2 topic echo /chatter",
    ("demo_nodes_cpp", "*"): "ros2 run demo_nodes_cpp parameter_blackboard",
    ("turtlesim", "*"): "ros2 run turtlesim turtlesim_node",
}
_CPP_PACKAGES = ("demo_nodes_cpp", "turtlesim", "examples_rclcpp", "rclcpp", "composition")


def absent_program_hint(package: str, executable: str) -> str | None:
    """Return one line for a docs' program the course cannot run, else None."""
    closest = _CLOSEST.get((package, executable)) or _CLOSEST.get((package, "*"))
    instead = f"the closest the course has is `{closest or 'ros2 pkg executables'}`."
    if package == "demo_nodes_py":
        missing = (
            f"`ros2 run {package} {executable}` is not in the course ({package} has no wheel)"
        )
        return f"{missing}: {instead}"
    if closest is None and not (package.endswith("_cpp") or package.startswith(_CPP_PACKAGES)):
        return None
    return f"{_NEEDS_RCLCPP.format(package=package, executable=executable)}: {instead}"
