"""Find the `ros2` daemons of a domain, whoever started them (for the daemon tests)."""

from __future__ import annotations

from pathlib import Path

from course_lib.processes import process_environ

__all__ = ["daemon_pids"]


def daemon_pids(domain: str) -> list[int]:
    """Return the pids of the daemon processes serving `domain`."""
    pids = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            argv = (entry / "cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        env = process_environ(int(entry.name)) if b"course_lib.ros2.daemon" in argv else {}
        if env.get("ROS_DOMAIN_ID") == domain:
            pids.append(int(entry.name))
    return pids
