"""The workspace's builds run one job per core without colcon's load limit, also under make."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from course_lib.core.paths import REPO_ROOT
from course_lib.tools.workspace import make_flags

JOBS = f"-j{os.cpu_count() or 1}"


@pytest.mark.parametrize(
    ("inherited", "expected"),
    [
        ("", JOBS),
        (" --no-print-directory", f"--no-print-directory {JOBS}"),  # `make setup`'s own
        ("s", f"s {JOBS}"),  # make -s: single-letter flags come first, without a dash
    ],
)
def test_jobs_are_added_where_make_flags_set_none(inherited: str, expected: str) -> None:
    assert make_flags(inherited) == expected


@pytest.mark.parametrize(
    "inherited",
    [" -j4 --jobserver-auth=3,4", "-l3", "--jobs=3", " --load-average=2"],
)
def test_jobs_already_set_are_left_alone(inherited: str) -> None:
    assert make_flags(inherited) == inherited


def test_a_build_started_by_make_setup_gets_the_jobs(tmp_path: Path) -> None:
    """Under `make`, MAKEFLAGS always exists (empty, or " --no-print-directory"): setting it
    only where missing left colcon to add `-l<cores>`."""
    probe = "from course_lib.tools.workspace import build_env; print(build_env()['MAKEFLAGS'])"
    makefile = tmp_path / "Makefile"
    makefile.write_text(f'probe:\n\t@{sys.executable} -c "{probe}"\n')
    env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL")}
    env["PYTHONPATH"] = str(REPO_ROOT)
    for flags in ([], ["--no-print-directory"]):
        out = subprocess.run(
            ["make", *flags, "-f", str(makefile), "probe"],
            env=env,
            capture_output=True,
            text=True,
            check=True,
            timeout=60,
        ).stdout
        assert out.split()[-1] == JOBS, (flags, out)
