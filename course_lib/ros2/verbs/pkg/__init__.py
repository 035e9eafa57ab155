"""`ros2 pkg` and `ros2 run`: packages, their executables, new packages."""

from ...verbkit.registry import command

command("pkg", "Various package related sub-commands")
