"""`make test`: the whole suite (unit, integration, notebooks, browser) in one pytest run."""

from __future__ import annotations

import os
import subprocess
import sys

from .domain import DOMAIN_ENV
from .paths import NOTEBOOKS_DIR, REPO_ROOT
from .processes import NAME_ENV, OWNER_ENV, OWNER_NS_ENV, SPAWNED_ENV
from .session import SESSION_DOMAIN_ENV

__all__ = ["TEST_ENV", "independent_env", "pytest_argv", "run_tests"]

# What the runner fixes so that checked outputs never depend on the machine.
TEST_ENV = {
    "RCUTILS_COLORIZED_OUTPUT": "0",
    "PYTHONHASHSEED": "0",
    "MPLBACKEND": "Agg",
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


def pytest_argv(extra: list[str]) -> list[str]:
    """Return the pytest command line: tests/ and every notebook, two workers."""
    workers = "2" if (os.cpu_count() or 1) >= 2 else "0"
    notebooks = ["notebooks"] if any(NOTEBOOKS_DIR.glob("*.ipynb")) else []
    return [
        sys.executable,
        "-m",
        "pytest",
        "tests",
        *notebooks,
        "--nbval-lax",
        "--nbval-sanitize-with",
        "tests/nbval_sanitize.cfg",
        "-n",
        workers,
        "--dist",
        "loadfile",
        # Tests of real processes on 2 busy cores: one that fails is run again (up to twice)
        # and reported as a rerun, so an intermittent failure stays visible in the summary.
        "--reruns",
        "2",
        "--reruns-delay",
        "1",
        *extra,
    ]


def run_tests(extra: list[str]) -> int:
    """Run the suite with the test environment; return pytest's exit code."""
    env = {**os.environ, **TEST_ENV}
    code = subprocess.run(pytest_argv(extra), cwd=REPO_ROOT, env=env, check=False).returncode
    if code == 5:
        print("pytest collected no tests: the suite is missing.", file=sys.stderr)
    return code


def with_course_interfaces(packages_stdout: str) -> str:
    """Add the interface packages the course builds (tf2_msgs) to `ros2 interface packages`.

    The golden transcripts were taken on the wheels alone; with the course's workspace
    sourced, the real tool lists its interface packages too, in the same sorted list.
    """
    from .paths import WORKSPACE_INSTALL_DIR

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
    from .paths import WORKSPACE_INSTALL_DIR

    header, *entries = list_stdout.splitlines()
    built = {
        f"    {path.parent.parent.name}/srv/{path.stem}"
        for path in (WORKSPACE_INSTALL_DIR / "share").glob("*/srv/*.srv")
    }
    return "".join(f"{line}\n" for line in [header, *sorted(set(entries) | built)])
