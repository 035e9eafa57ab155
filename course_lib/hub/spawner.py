"""The learners' servers: JupyterHub's local-process spawner, tied to the hub and cleaned after."""

from __future__ import annotations

import asyncio
import pwd
import signal
from collections.abc import Callable
from typing import Any

from jupyterhub.spawner import LocalProcessSpawner, set_user_setuid

from ..signalling import send
from .tied import tie_to_parent

__all__ = ["CourseSpawner"]

STOP_TIMEOUT_S = 60.0


class CourseSpawner(LocalProcessSpawner):
    """Runs `python -m course_lib hub-lab` as the learner's Unix account.

    The server gets SIGTERM if the hub dies, and once it has stopped, the learner's leftover
    course processes (if any) are stopped the way `make stop` does, run as the learner.
    """

    def make_preexec_fn(self, name: str) -> Callable[[], None]:
        become_user = set_user_setuid(name)

        def preexec() -> None:
            become_user()
            tie_to_parent()  # after setuid: changing the user clears the parent-death signal

        return preexec

    async def stop_leftovers(self) -> None:
        """Run `python -m course_lib stop` as the learner; log what it stopped."""
        account = pwd.getpwnam(self.user.name)
        env = {"HOME": account.pw_dir, "USER": self.user.name, "PATH": self.environment["PATH"]}
        process = await asyncio.create_subprocess_exec(
            self.cmd[0], "-m", "course_lib", "stop",
            preexec_fn=set_user_setuid(self.user.name), env=env, cwd=account.pw_dir,
            stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT,
        )  # fmt: skip
        try:
            output, _ = await asyncio.wait_for(process.communicate(), STOP_TIMEOUT_S)
        except TimeoutError:
            send(process.pid, signal.SIGKILL, reason="`course_lib stop` after a server hung")
            self.log.warning("Stopping %s's leftover processes took too long", self.user.name)
            return
        text = output.decode(errors="replace").strip()
        self.log.info("After %s's server stopped: %s", self.user.name, text or "nothing left")


async def stop_leftovers_hook(spawner: Any) -> None:
    """JupyterHub's post-stop hook: see CourseSpawner.stop_leftovers."""
    await spawner.stop_leftovers()
