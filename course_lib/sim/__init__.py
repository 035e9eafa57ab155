"""The simulated TurtleBot3 Waffle Pi: MuJoCo physics, ROS 2 bridge, and the notebook handle.

Lesson 3 starts it with `start_world()`; lesson 7 drives it with the `velocity` parameter.
"""

from .kinematics import DiffDrive, Pose2D

__all__ = ["DiffDrive", "Pose2D", "World", "start_world"]


def __getattr__(name: str):
    if name == "World":
        from .world import World

        return World
    if name == "start_world":
        from .start import start_world

        return start_world
    raise AttributeError(name)
