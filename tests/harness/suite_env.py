"""The environment of the suite's processes: the one stored outputs are checked in, and the one
a test gives a process that starts a course session of its own."""

from __future__ import annotations

import os

from course_lib.processes.domain import DOMAIN_ENV
from course_lib.processes.orphans import NAME_ENV, OWNER_ENV, OWNER_NS_ENV, SPAWNED_ENV
from course_lib.session.session import SESSION_DOMAIN_ENV
from course_lib.tools.notebook_outputs import OUTPUT_ENV

__all__ = ["TEST_ENV", "independent_env"]

TEST_ENV = OUTPUT_ENV  # what the runner fixes: checked outputs never depend on the machine


def independent_env(**extra: str) -> dict[str, str]:
    """Return the environment for a process that starts a course session of its own.

    Like a fresh `make lab` or kernel: this process's domain, owner tag and lab are left out
    (the child leases a domain itself), and the test settings are in.
    """
    own: tuple[str, ...] = (DOMAIN_ENV, SESSION_DOMAIN_ENV, OWNER_ENV, OWNER_NS_ENV)
    own += (NAME_ENV, SPAWNED_ENV, "COURSE_LAB")
    env = {k: v for k, v in os.environ.items() if k not in own}
    return {**env, **TEST_ENV, **extra}
