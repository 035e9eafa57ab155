"""What tests share: the environment the runner fixes, and goldens adjusted to the course.

The runner itself (`make test`) is course_lib.tools.suite.
"""

from __future__ import annotations

import os

from ..processes.children import NAME_ENV, OWNER_ENV, OWNER_NS_ENV, SPAWNED_ENV
from ..processes.domain import DOMAIN_ENV
from ..session.session import SESSION_DOMAIN_ENV

__all__ = ["TEST_ENV", "independent_env", "with_course_interfaces", "with_course_services"]

# What the runner fixes so that checked outputs never depend on the machine.
TEST_ENV = {
    "RCUTILS_COLORIZED_OUTPUT": "0",
    "PYTHONHASHSEED": "0",
    "IPYKERNEL_CELL_NAME": "<IPY-INPUT>",
    "PYDEVD_DISABLE_FILE_VALIDATION": "1",
}


def independent_env(**extra: str) -> dict[str, str]:
    """Return the environment for a process that starts a course session of its own.

    Like a fresh `make lab` or kernel: this process's domain, owner tag and lab are left out
    (the child leases a domain itself), and the test settings are in.
    """
    own = (DOMAIN_ENV, SESSION_DOMAIN_ENV, OWNER_ENV, OWNER_NS_ENV, NAME_ENV, SPAWNED_ENV)
    own += ("COURSE_LAB",)
    env = {k: v for k, v in os.environ.items() if k not in own}
    return {**env, **TEST_ENV, **extra}


def with_course_interfaces(packages_stdout: str) -> str:
    """Add the interface packages the course builds (tf2_msgs) to `ros2 interface packages`.

    The golden transcripts were taken on the wheels alone; with the course's workspace
    sourced, the real tool lists its interface packages too, in the same sorted list.
    """
    from ..core.paths import WORKSPACE_INSTALL_DIR

    share = WORKSPACE_INSTALL_DIR / "share"
    built = {
        p.name for p in share.glob("*") if any((p / kind).is_dir() for kind in ("msg", "srv"))
    }
    lines = sorted(set(packages_stdout.splitlines()) | built)
    return "".join(f"{line}\n" for line in lines)


def with_course_services(list_stdout: str) -> str:
    """Add the services the course builds (turtlesim's) to `ros2 interface list -s`'s golden.

    Taken on the wheels alone, like `with_course_interfaces`; the real tool lists every
    installed service in one sorted list under "Services:".
    """
    from ..core.paths import WORKSPACE_INSTALL_DIR

    header, *entries = list_stdout.splitlines()
    built = {
        f"    {path.parent.parent.name}/srv/{path.stem}"
        for path in (WORKSPACE_INSTALL_DIR / "share").glob("*/srv/*.srv")
    }
    return "".join(f"{line}\n" for line in [header, *sorted(set(entries) | built)])
