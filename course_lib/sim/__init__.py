"""The simulated TurtleBot3 Waffle Pi: MuJoCo physics, its ROS 2 nodes, its live 3D view.

`python -m course_lib.sim` runs the whole world as one process (`world_process`); `launcher`
starts it with its meshcat viewer. A notebook's handle on it is `course_lib.notebook.World`
(lesson 3 starts it with `start_world()`; lesson 7 drives it with the `velocity` parameter).
"""

from .world.kinematics import DiffDrive, Pose2D

__all__ = ["DiffDrive", "Pose2D"]
