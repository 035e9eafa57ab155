"""The progress service as the class hub runs it: on a socket bound once, as its own account,
started again whenever it dies.

The launcher (root) binds the service's port (127.0.0.1, one the kernel picks) and hands the
listening socket to the service as an inherited file descriptor: no other process can take
the port between its choice and its use, as one could when a free port was picked, closed
and bound again later. The launcher keeps its copy open for the hub's whole life and starts
the service again on it when it dies (KeptService): a dead service's port is never free for
another account to bind and receive the learners' self-checks with their tokens; what comes
while it is down waits in the socket's queue. The service runs as SERVICE_ACCOUNT, a system
account of its own (no shell, no home, no group but its own), which owns only the folder of
its records.
"""

from __future__ import annotations

import collections
import os
import pwd
import signal
import socket
import stat
import subprocess
import threading
import time
from collections.abc import Callable, Mapping
from pathlib import Path

from ..core.errors import CourseError
from .guard.tied import tie_to_parent
from .progress import service_command

__all__ = [
    "SERVICE_ACCOUNT",
    "KeptService",
    "bind_service_socket",
    "records_folder",
    "start_service",
    "stop_service",
]

SERVICE_ACCOUNT = "ros2-course-progress"
STOP_TIMEOUT_S = 10.0
RESTART_BURST = 5  # starts at most in RESTART_WINDOW_S: a service that dies at once waits
RESTART_WINDOW_S = 60.0


def bind_service_socket(host: str = "127.0.0.1") -> socket.socket:
    """Return a listening TCP socket on `host`, on a port the kernel picked (held from now)."""
    listener = socket.create_server((host, 0), backlog=64)
    listener.set_inheritable(False)  # passed to the service by pass_fds only
    return listener


def records_folder(state: Path, account: pwd.struct_passwd | None) -> Path:
    """Return the service's folder beside the hub's `state` (which stays root's alone), owned
    by `account`, private to it; records an earlier hub kept in `state` move there."""
    folder = state.parent / f"{state.name}-progress"
    closed = [p for p in folder.parents if not p.stat().st_mode & stat.S_IXOTH]
    if account is not None and closed:
        raise CourseError(
            f"The progress service runs as {account.pw_name!r} and cannot reach {folder}: "
            f"{closed[0]} is closed to other accounts.",
            hint="set `state:` in config/hub.yaml to a folder in one every account may enter "
            "(the default, /var/lib/ros2-params-course, is).",
        )
    folder.mkdir(mode=0o700, exist_ok=True)
    if folder.is_symlink() or not folder.is_dir():
        raise CourseError(f"{folder} is not a folder.", hint="remove it, start the hub again.")
    old = state / "progress.sqlite"
    if old.exists() and not (folder / old.name).exists():
        old.rename(folder / old.name)
    if account is not None:
        for path in (folder, *folder.iterdir()):
            os.lchown(path, account.pw_uid, account.pw_gid)
    folder.chmod(0o700)
    return folder


def _become(account: pwd.struct_passwd | None, parent: int) -> Callable[[], None]:
    def preexec() -> None:
        if account is not None:
            os.setgroups([])
            os.setgid(account.pw_gid)
            os.setuid(account.pw_uid)
        tie_to_parent(signal.SIGTERM, parent=parent)  # after setuid, which clears it

    return preexec


def start_service(
    python: str,
    db: Path,
    listener: socket.socket,
    environment: Mapping[str, str],
    account: pwd.struct_passwd | None = None,
) -> subprocess.Popen[bytes]:
    """Start the service on `listener` (the caller may close its copy after), as `account`
    (None: as this process's user), tied to this process (it stops when this one dies)."""
    fd = listener.fileno()
    env = {
        "PATH": "/usr/bin:/bin",
        "LANG": os.environ.get("LANG", "C.UTF-8"),
        "HOME": account.pw_dir if account is not None else os.environ.get("HOME", "/"),
        **environment,
    }
    return subprocess.Popen(
        [*service_command(python, db), "--listen-fd", str(fd)],
        env=env, cwd="/", pass_fds=(fd,), preexec_fn=_become(account, os.getpid()),
    )  # fmt: skip


def stop_service(service: subprocess.Popen[bytes]) -> None:
    """Stop the service (SIGTERM, then SIGKILL after a while); idempotent."""
    if service.poll() is None:
        service.send_signal(signal.SIGTERM)
        try:
            service.wait(STOP_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            service.kill()
            service.wait()


def _ended(process: subprocess.Popen[bytes]) -> str:
    code = process.returncode
    if code is not None and code < 0:
        return f"killed by {signal.Signals(-code).name}"
    return f"exit status {code}"


class KeptService:
    """A service started by `start`, started again each time it dies, at most `burst` times
    in `window_s` (then it waits); each death is said through `log` (the hub's output).

    Restarts come from a thread of the keeper's: the kernel's parent-death signal follows the
    thread that started a child, and this one lives until `stop`.
    """

    def __init__(
        self,
        start: Callable[[], subprocess.Popen[bytes]],
        name: str,
        *,
        log: Callable[[str], None] = print,
        burst: int = RESTART_BURST,
        window_s: float = RESTART_WINDOW_S,
    ) -> None:
        self._start, self.name, self._log, self.window_s = start, name, log, window_s
        self._starts: collections.deque[float] = collections.deque(maxlen=burst)
        self._lock = threading.Lock()
        self._stopping = threading.Event()
        self.process = self._begin()  # here: a service that cannot start at all is an error
        self._thread = threading.Thread(target=self._keep, name=f"keep {name}", daemon=True)
        self._thread.start()

    def _begin(self) -> subprocess.Popen[bytes]:
        self._starts.append(time.monotonic())
        return self._start()

    def _pause(self) -> float:
        """Return how long to wait before the next start (0 below `burst` starts a window)."""
        if len(self._starts) < (self._starts.maxlen or 1):
            return 0.0
        return max(0.0, self._starts[0] + self.window_s - time.monotonic())

    def _keep(self) -> None:
        while True:
            ended = self.process
            ended.wait()
            pause = self._pause()
            if not self._stopping.is_set() and pause > 0:
                self._log(
                    f"{self.name} stopped {len(self._starts)} times in {self.window_s:.0f} s "
                    f"({_ended(ended)}): it starts again in {pause:.0f} s; its port stays held."
                )
            if self._stopping.wait(pause):
                return
            with self._lock:
                if self._stopping.is_set():
                    return
                try:
                    self.process = self._begin()
                except Exception as error:  # tried again at the same bounded rate
                    self._log(f"{self.name} could not start again: {error}")
                    continue
            self._log(
                f"{self.name} stopped ({_ended(ended)}); started again on the same socket "
                f"(pid {self.process.pid}): its port stayed the hub's."
            )

    def stop(self) -> None:
        """Stop the service and start it no more; idempotent."""
        with self._lock:
            self._stopping.set()
            process = self.process
        stop_service(process)
        self._thread.join(STOP_TIMEOUT_S)
