"""`ros2 launch` for the course: real ROS 2 launch files (Python, XML, YAML), run unchanged.

The `launch`/`launch_ros` modules that launch files import exist only inside the process
that evaluates them (see `shim`). `launch(...)` starts a launch from a notebook (lesson 10);
`dry_run(...)` shows each node's parameters and where they come from.
"""

from .dry_run import DryRunReport, dry_run
from .handle import LaunchHandle, launch

__all__ = ["DryRunReport", "LaunchHandle", "dry_run", "launch"]
