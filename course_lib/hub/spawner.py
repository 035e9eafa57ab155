"""The learners' servers: JupyterHub's local-process spawner, tied to the hub and cleaned after."""

from __future__ import annotations

import asyncio
import pwd
import signal
from collections.abc import Callable
from typing import Any

from jupyterhub.spawner import LocalProcessSpawner, set_user_setuid

from ..core.signalling import send
from .tied import tie_to_parent

__all__ = ["CourseSpawner", "leftover_stop_argv", "run_bounded"]

STOP_TIMEOUT_S = 60.0
OUTPUT_LIMIT = 16384  # bytes of its output the hub keeps for its log


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
        text = await run_bounded(
            leftover_stop_argv(self.cmd[0]), env=env, preexec_fn=set_user_setuid(self.user.name)
        )
        if text is None:
            self.log.warning("Stopping %s's leftover processes took too long", self.user.name)
            return
        self.log.info("After %s's server stopped: %s", self.user.name, text or "nothing left")


def leftover_stop_argv(python: str) -> list[str]:
    """Return `python -m course_lib stop`, isolated: nothing of the learner's is imported.

    `-I` leaves the current folder, PYTHON* variables and the user's site-packages out of the
    import path, so a `course_lib` folder the learner planted is never the one that runs.
    """
    return [python, "-I", "-m", "course_lib", "stop"]


async def run_bounded(
    argv: list[str],
    *,
    env: dict[str, str],
    preexec_fn: Callable[[], None] | None = None,
    timeout: float = STOP_TIMEOUT_S,
) -> str | None:
    """Run `argv` in `/`; return the start of its output (OUTPUT_LIMIT bytes), None if it hung."""
    process = await asyncio.create_subprocess_exec(
        *argv, preexec_fn=preexec_fn, env=env, cwd="/",
        stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT,
    )  # fmt: skip
    assert process.stdout is not None

    async def collect() -> bytes:
        kept = bytearray()
        while chunk := await process.stdout.read(65536):  # type: ignore[union-attr]
            kept += chunk[: max(0, OUTPUT_LIMIT - len(kept))]  # the rest is read, not kept
        await process.wait()
        return bytes(kept)

    try:
        output = await asyncio.wait_for(collect(), timeout)
    except TimeoutError:
        send(process.pid, signal.SIGKILL, reason="`course_lib stop` after a server hung")
        await process.wait()
        return None
    return output.decode(errors="replace").strip()


async def stop_leftovers_hook(spawner: Any) -> None:
    """JupyterHub's post-stop hook: see CourseSpawner.stop_leftovers."""
    await spawner.stop_leftovers()
