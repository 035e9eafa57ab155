"""The golden transcripts adjusted to the course: taken on the wheels alone, while the course's
workspace adds interface packages (tf2_msgs) and services (turtlesim's) that the real tool lists
in the same sorted lists."""

from __future__ import annotations

from course_lib.core.paths import WORKSPACE_INSTALL_DIR

__all__ = ["with_course_interfaces", "with_course_services"]


def with_course_interfaces(packages_stdout: str) -> str:
    """Add the interface packages the course builds to `ros2 interface packages`' golden."""
    share = WORKSPACE_INSTALL_DIR / "share"
    built = {
        p.name for p in share.glob("*") if any((p / kind).is_dir() for kind in ("msg", "srv"))
    }
    lines = sorted(set(packages_stdout.splitlines()) | built)
    return "".join(f"{line}\n" for line in lines)


def with_course_services(list_stdout: str) -> str:
    """Add the services the course builds to `ros2 interface list -s`' golden (under
    "Services:")."""
    header, *entries = list_stdout.splitlines()
    built = {
        f"    {path.parent.parent.name}/srv/{path.stem}"
        for path in (WORKSPACE_INSTALL_DIR / "share").glob("*/srv/*.srv")
    }
    return "".join(f"{line}\n" for line in [header, *sorted(set(entries) | built)])
