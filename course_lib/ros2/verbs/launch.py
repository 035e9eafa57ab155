"""`ros2 launch ...`: handed to course_lib.launch, which parses its own arguments and prints."""

from __future__ import annotations

from .context import Context

__all__ = ["main"]


def main(argv: list[str], ctx: Context) -> int:
    """Run `ros2 launch <argv>` (it prints straight to this process)."""
    try:
        from ...launch.command import cli as launch_cli
    except ImportError as exc:
        ctx.console.err(f"ros2 launch is not available in this course yet ({exc}).\n")
        return 1
    return int(launch_cli.main(argv) or 0)
