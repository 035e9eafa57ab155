"""Start child processes that never outlive their owner.

Every child runs in its own process group with ``PR_SET_PDEATHSIG`` set, so the kernel
kills it when the spawning thread dies, whatever the cause (SIGKILL included). Linux ties
that signal to the *thread* that forked, so all children are forked from one long-lived
spawner thread. Each child also carries its owner's tags (orphans.py), by which a later
session finds and kills what a crashed one left behind.
"""

from __future__ import annotations

import contextlib
import ctypes
import logging
import os
import queue
import re
import signal
import subprocess
import threading
import time
from collections import deque
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import Future
from dataclasses import dataclass
from typing import IO, Any, TypeVar

from ..core.errors import ProcessStartError
from ..core.host import procfs
from ..core.host.signalling import send
from ..core.paths import REPO_ROOT
from .orphans import (
    CLONE_ENV,
    NAME_ENV,
    OWNER_ENV,
    OWNER_NS_ENV,
    SPAWNED_ENV,
    command_tag,
    owner_tag,
)
from .output_lines import output_lines

__all__ = [
    "ChildProcess",
    "OutputLine",
    "set_parent_death_signal",
    "spawn",
]

_PR_SET_PDEATHSIG = 1
_MAX_LINES = 5000
_REAP_WAIT_S = 10.0  # after a child closed its output, at most, until it exits
_TRACEBACK = "Traceback (most recent call last)"
_LOGGED_ERROR = re.compile(r"\[(ERROR|FATAL)\] ")  # a ROS log line's level
_NEXT_LINE_WAIT_S = 2.0  # after a first line at ERROR: does a traceback follow?
T = TypeVar("T")
_LIBC = ctypes.CDLL(None, use_errno=True)  # loaded once: preexec must not load libraries
_log = logging.getLogger(__name__)


@dataclass(frozen=True)
class OutputLine:
    """One line a child printed, without its line ending."""

    stream: str
    text: str
    time: float


def set_parent_death_signal(sig: int, parent_pid: int) -> None:
    """Have the kernel send `sig` to this process when its parent dies; exit at once if
    `parent_pid` (the parent when this was decided) is already gone. Safe in a preexec_fn."""
    _LIBC.prctl(_PR_SET_PDEATHSIG, int(sig), 0, 0, 0)
    if os.getppid() != parent_pid:  # the parent died before prctl took effect
        os._exit(1)


class _SpawnerThread:
    """The one thread every child is forked from, alive until the process itself ends.

    A daemon thread, not a pool's worker: Python joins pool workers at exit *before* atexit
    handlers run, and the kernel would then SIGKILL every child (the death signal follows the
    forking thread), so a session's atexit stop would never reach a child alive. A node killed
    that way leaves its DDS participant in the graph until its lease runs out.
    """

    def __init__(self) -> None:
        self._work: queue.SimpleQueue[tuple[Callable[[], Any], Future[Any]]] = queue.SimpleQueue()
        self._lock = threading.Lock()
        self._thread: threading.Thread | None = None

    def run(self, start: Callable[[], T]) -> T:
        """Run `start` on the spawner thread and return its result (or raise its error)."""
        with self._lock:
            if self._thread is None or not self._thread.is_alive():
                self._thread = threading.Thread(
                    target=self._serve, name="course-spawner", daemon=True
                )
                self._thread.start()
        done: Future[T] = Future()
        self._work.put((start, done))
        return done.result()

    def _serve(self) -> None:
        while True:
            start, done = self._work.get()
            try:
                done.set_result(start())
            except BaseException as exc:  # handed to the caller, who raises it
                done.set_exception(exc)


_spawner = _SpawnerThread()


def _die_with_parent(parent_pid: int) -> Callable[[], None]:
    def preexec() -> None:
        set_parent_death_signal(signal.SIGKILL, parent_pid)

    return preexec


class ChildProcess:
    """A running child: its output (bounded), its exit status, and how to stop it."""

    def __init__(
        self,
        popen: subprocess.Popen[bytes],
        name: str,
        argv: Sequence[str],
        respawn: Callable[[], subprocess.Popen[bytes]] | None = None,
    ) -> None:
        self.name = name
        self.argv = list(argv)
        self._respawn = respawn
        self._lines: deque[OutputLine] = deque(maxlen=_MAX_LINES)
        self._listeners: list[Callable[[OutputLine], None]] = []
        self._cond = threading.Condition()
        self._attach(popen)

    def _attach(self, popen: subprocess.Popen[bytes]) -> None:
        self._popen = popen
        # Read while the child is not reaped yet, so `popen.pid` still names it.
        self._started = procfs.holder_start(popen.pid)
        self._group_cleared = False
        started = time.monotonic()
        self._readers = [
            threading.Thread(target=self._read, args=(pipe, stream, started), daemon=True)
            for pipe, stream in ((popen.stdout, "stdout"), (popen.stderr, "stderr"))
            if pipe is not None
        ]
        for reader in self._readers:
            reader.start()

    def __repr__(self) -> str:
        state = "running" if self.alive else f"exited {self.returncode}"
        return f"<ChildProcess {self.name} pid={self.pid} {state}>"

    @property
    def pid(self) -> int:
        return self._popen.pid

    @property
    def returncode(self) -> int | None:
        return self._popen.poll()

    @property
    def alive(self) -> bool:
        # poll() says None while another thread waits on the child: ask /proc too (a zombie
        # is dead), so a killed child never looks alive.
        return self._popen.poll() is None and procfs.pid_alive(self.pid)

    @property
    def lines(self) -> list[OutputLine]:
        with self._cond:
            return list(self._lines)

    def text(self, stream: str | None = None) -> str:
        """Return what the child printed so far (one stream, or both interleaved)."""
        return "".join(f"{ln.text}\n" for ln in self.lines if stream in (None, ln.stream))

    def add_listener(self, listener: Callable[[OutputLine], None]) -> None:
        with self._cond:
            self._listeners.append(listener)

    def remove_listener(self, listener: Callable[[OutputLine], None]) -> None:
        with self._cond, contextlib.suppress(ValueError):
            self._listeners.remove(listener)

    def _read(self, pipe: IO[bytes], stream: str, started: float) -> None:
        for raws, read_at in output_lines(pipe, started):
            lines = [
                OutputLine(stream, raw.decode("utf-8", "replace").rstrip("\r"), read_at)
                for raw in raws
            ]
            with self._cond:
                self._lines.extend(lines)
                listeners = list(self._listeners)
                self._cond.notify_all()
            for line in lines:
                for listener in listeners:
                    try:
                        listener(line)
                    except Exception:  # never stops the reading: logged once, then dropped
                        _log.exception("a reader of %s's output failed; it is dropped", self.name)
                        self.remove_listener(listener)
                        listeners = [known for known in listeners if known is not listener]
        pipe.close()
        if stream == "stdout":
            # The output ended: the child has exited or soon will. Reap it here, so that a
            # child stopped from elsewhere (another notebook's lesson, `make stop`) never stays
            # a zombie until its owner happens to ask about it.
            with contextlib.suppress(subprocess.TimeoutExpired):
                self._popen.wait(timeout=_REAP_WAIT_S)
        with self._cond:
            self._cond.notify_all()

    def wait_for_line(
        self, match: str | Callable[[OutputLine], bool], timeout: float
    ) -> OutputLine | None:
        """Wait until a line matches a regex or predicate; None on timeout or exit."""
        test = (
            (lambda ln: re.search(match, ln.text) is not None) if isinstance(match, str) else match
        )
        deadline = time.monotonic() + timeout
        seen = 0
        with self._cond:
            while True:
                lines = list(self._lines)
                for line in lines[seen:]:
                    if test(line):
                        return line
                seen = len(lines)
                remaining = deadline - time.monotonic()
                if remaining <= 0 or (not self.alive and not self._readers_running()):
                    return None
                self._cond.wait(min(remaining, 0.1))

    def wait_for_start(self, timeout: float, *, crash_wait: float = 10.0) -> OutputLine | None:
        """Wait for the first line and return it. A traceback (the process is failing) is
        waited for to its end, up to `crash_wait` s more, as is a traceback that follows a
        first line at ERROR or FATAL (rcl's "Failed to parse global arguments" then rclpy's)."""
        first = self.wait_for_line(lambda _line: True, timeout)
        if first is None:
            return None
        if _LOGGED_ERROR.match(first.text):
            then = self.wait_for_line(lambda line: line is not first, _NEXT_LINE_WAIT_S)
            failing = then is not None and then.text.startswith(_TRACEBACK)
        else:
            failing = first.text.startswith(_TRACEBACK)
        if failing:
            self.wait(crash_wait)
        return first

    def _readers_running(self) -> bool:
        return any(reader.is_alive() for reader in self._readers)

    def wait(self, timeout: float | None = None) -> int | None:
        """Wait for the child to exit and its output to be read; None on timeout."""
        try:
            code = self._popen.wait(timeout)
        except subprocess.TimeoutExpired:
            return None
        for reader in self._readers:
            reader.join(timeout=1.0)
        return code

    def send_signal(self, sig: int, *, reason: str = "") -> None:
        """Send `sig` to the child's whole process group."""
        if self.alive:
            with contextlib.suppress(ProcessLookupError, PermissionError):
                send(self.pid, sig, group=True, reason=reason or f"stopping {self.name}")

    def stop(self, *, timeout: float = 5.0) -> int:
        """Stop the child like Ctrl-C would, escalating to SIGTERM and SIGKILL; idempotent."""
        for sig, grace in ((signal.SIGINT, timeout), (signal.SIGTERM, 2.0), (signal.SIGKILL, 2.0)):
            if not self.alive:
                break
            self.send_signal(sig)
            self.wait(grace)
        code = self.wait(timeout=2.0)
        self._kill_group_left()
        return code if code is not None else -signal.SIGKILL

    def _kill_group_left(self) -> None:
        """SIGKILL what the child left in its process group (grandchildren), never another's.

        Once the child is reaped its pid is free, and a later process may get it: everything
        `spawn` starts leads a group of its own, so a `killpg` on that pid would kill another
        session's process (another lab's JupyterLab, another kernel's node). The group is
        killed only while no other process holds the pid, and only once after the child ended.
        """
        if self._group_cleared:
            return
        holder = procfs.holder_start(self.pid)
        if holder is not None and holder != self._started:
            self._group_cleared = True  # the pid names another process now: not our group
            return
        self._group_cleared = self._popen.poll() is not None
        with contextlib.suppress(ProcessLookupError, PermissionError):
            send(
                self.pid, signal.SIGKILL, group=True, reason=f"what {self.name} left in its group"
            )

    def restart(self, *, timeout: float = 5.0) -> ChildProcess:
        """Stop the child if it still runs, then start the same command again in this handle.

        Same argv, environment and folder (so a node comes back with its params file); the
        pid changes and the output of the new run is appended to `lines`.
        """
        if self._respawn is None:
            raise ProcessStartError(f"{self.name} cannot be restarted: it was not spawned here.")
        self.stop(timeout=timeout)
        for reader in self._readers:
            reader.join(timeout=1.0)
        try:
            popen = self._respawn()
        except OSError as exc:
            raise ProcessStartError(f"Could not restart {self.name}: {exc}") from exc
        self._attach(popen)
        return self


def spawn(
    argv: Sequence[str],
    *,
    name: str,
    env: Mapping[str, str] | None = None,
    cwd: str | os.PathLike[str] | None = None,
    new_session: bool = True,
    merge_stderr: bool = False,
    capture: bool = True,
) -> ChildProcess:
    """Start `argv` as a child that dies with this process and return its handle."""
    child_env = dict(os.environ if env is None else env)
    child_env[OWNER_ENV] = owner_tag()
    child_env[OWNER_NS_ENV] = procfs.pid_namespace()
    child_env[NAME_ENV] = name
    child_env[SPAWNED_ENV] = command_tag(argv)
    child_env[CLONE_ENV] = str(REPO_ROOT)
    child_env.setdefault("PYTHONUNBUFFERED", "1")
    pipe = subprocess.PIPE if capture else None

    def start() -> subprocess.Popen[bytes]:
        return subprocess.Popen(
            list(argv),
            env=child_env,
            cwd=cwd,
            stdin=subprocess.DEVNULL if capture else None,
            stdout=pipe,
            stderr=(subprocess.STDOUT if merge_stderr else pipe) if capture else None,
            start_new_session=new_session,
            preexec_fn=_die_with_parent(os.getpid()),
            close_fds=True,
        )

    try:
        popen = _spawner.run(start)
    except OSError as exc:
        raise ProcessStartError(
            f"Could not start {name}: {exc.strerror or exc}",
            hint=f"check that `{argv[0]}` exists and is executable (`make setup` rebuilds it).",
        ) from exc
    return ChildProcess(popen, name, argv, respawn=lambda: _spawner.run(start))
