"""The hub's own locks: files no other account can open, waited on for a bounded time.

Two `make hub` started at once must not build the learners' environment (or install the
proxy) in one folder together, so each holds a lock while it does. A lock file in a folder
every account can read is one every account can open and `flock` too, and `make hub` then
waited, silently, as long as that account liked. These live in `<environment>/.locks/`,
root's alone (0700), so only the hub's own account can hold them; a hub that still waits
longer than `timeout` (another hub's build that hangs) says who holds the lock and stops.
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import time
from collections.abc import Callable, Iterator
from pathlib import Path

from ...core.errors import CourseError
from ...core.host.procfs import cmdline
from .root_folder import root_only_folder

__all__ = ["LOCKS_FOLDER", "LOCK_TIMEOUT_S", "LockWaitError", "hub_lock", "lock_holders"]

LOCKS_FOLDER = ".locks"  # in the learners' environment; never opened to other accounts
LOCK_TIMEOUT_S = 1800.0  # a first build takes minutes on a slow host; a hung one, forever
_POLL_S = 0.5
_LEGACY = (".build.lock", ".proxy.lock")  # where older hubs kept them, open to all


class LockWaitError(CourseError):
    """Another process held one of the hub's locks for longer than the hub waits."""


def _private_folder(environment: Path) -> Path:
    """Return `<environment>/.locks`, made (or made again) a folder of this account alone."""
    folder = root_only_folder(environment / LOCKS_FOLDER)
    for name in _LEGACY:  # an account may hold one open: it no longer stops anything
        (environment / name).unlink(missing_ok=True)
    return folder


def lock_holders(path: Path) -> list[int]:
    """Return the pids holding a `flock` on the file at `path` (from /proc/locks)."""
    try:
        info = path.stat()
        text = Path("/proc/locks").read_text()
    except OSError:
        return []
    wanted = f"{os.major(info.st_dev):02x}:{os.minor(info.st_dev):02x}:{info.st_ino}"
    holders = []
    for line in text.splitlines():
        fields = line.split()
        # "1: FLOCK  ADVISORY  WRITE 1234 08:01:5678 0 EOF"; waiters have "->" after the id
        if len(fields) >= 6 and fields[1] == "FLOCK" and fields[5] == wanted:
            with contextlib.suppress(ValueError):
                holders.append(int(fields[4]))
    return holders


def _named(pids: list[int]) -> str:
    named = []
    for pid in pids:
        command = " ".join(cmdline(pid) or ())[:120]
        named.append(f"pid {pid} ({command})" if command else f"pid {pid}")
    return ", ".join(named) or "a process that has ended"


@contextlib.contextmanager
def hub_lock(
    environment: Path,
    name: str,
    what: str,
    *,
    say: Callable[[str], None] = print,
    timeout: float = LOCK_TIMEOUT_S,
) -> Iterator[None]:
    """Hold the hub's lock `name` of `environment` for the block: `what` (a few words, "the
    build of the learners' environment") is what it guards. Waits at most `timeout` seconds,
    saying once who holds it; then raises LockWaitError naming them."""
    path = _private_folder(environment) / name
    fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_CLOEXEC, 0o600)
    try:
        os.fchmod(fd, 0o600)
        deadline = time.monotonic() + timeout
        told = False
        while True:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                holders = _named(lock_holders(path))
                if time.monotonic() >= deadline:
                    raise LockWaitError(
                        f"Waited {timeout:.0f} s for {what}, held by {holders}.",
                        hint="if that hub is stuck, stop it (Ctrl-C, or `kill` that pid), "
                        "then start this one again.",
                    ) from None
                if not told:
                    say(f"Waiting for {what}, which another hub is doing ({holders}) ...")
                    told = True
                time.sleep(_POLL_S)
        yield
    finally:
        os.close(fd)
