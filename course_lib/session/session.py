"""One course session: a private ROS domain, one rclpy client node, and every child process.

Lesson 1 introduces it; every other part of the course (the `ros2` commands, the
simulation, the viewer, launch) runs through the session of the current process.
"""

from __future__ import annotations

import atexit
import contextlib
import logging
import os
import threading
import time
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from ..core import ament, param_journal
from ..core.errors import SessionClosedError, SessionThreadError
from ..core.paths import PACKAGE_DIR
from ..processes.children import ChildProcess, spawn
from ..processes.domain import DOMAIN_ENV, isolation_env, lease_domain
from ..processes.orphans import reap_orphans
from ..processes.shm_segments import sweep_stale_segments

if TYPE_CHECKING:  # rclpy is imported when a node starts, not with this module
    from rclpy.parameter import Parameter
    from rclpy.task import Future

__all__ = [
    "FASTDDS_PROFILE",
    "ROS_DISTRO_ENV",
    "SESSION_DOMAIN_ENV",
    "Session",
    "close_current_session",
    "get_session",
    "session_env",
]

FASTDDS_PROFILE = PACKAGE_DIR / "dds" / "fastdds_profile.xml"
_PROFILE_ENV = "FASTRTPS_DEFAULT_PROFILES_FILE"
SESSION_DOMAIN_ENV = "COURSE_SESSION_DOMAIN"  # marks a ROS_DOMAIN_ID we set ourselves
# What a real Jazzy's setup.bash exports: the docs' commands use $ROS_DISTRO.
ROS_DISTRO_ENV = {"ROS_DISTRO": "jazzy", "ROS_VERSION": "2", "ROS_PYTHON_VERSION": "3"}
_log = logging.getLogger(__name__)


def _explicit_env() -> dict[str, str]:
    """Return os.environ without a domain id that an earlier session of ours put there."""
    env = dict(os.environ)
    if env.get(SESSION_DOMAIN_ENV) and env.get(DOMAIN_ENV) == env[SESSION_DOMAIN_ENV]:
        env.pop(DOMAIN_ENV)
    return env


def session_env(domain_id: int, base: Mapping[str, str] | None = None) -> dict[str, str]:
    """Return the environment of a session's processes: isolation, fast discovery, workspace."""
    env = ament.workspace_env(base)
    env.pop("ROS_LOCALHOST_ONLY", None)  # it would override the discovery range
    env.update(isolation_env(domain_id))
    env.setdefault(_PROFILE_ENV, str(FASTDDS_PROFILE))
    env.setdefault("RCUTILS_LOGGING_BUFFERED_STREAM", "0")
    env.update(ROS_DISTRO_ENV)
    return env


class SpinningNode:
    """One rclpy node in a context of its own, spun by one executor thread until close().

    The one way the course builds a client node: the kernel's Session and the `ros2`
    command's DirectNode. No signal handlers (the kernel and the command keep theirs), no
    parameter services; no `~/get_type_description` service unless asked (as ros2cli's
    daemon: that service's messages import numpy, about 9 MiB in every process).
    """

    def __init__(
        self,
        name: str,
        *,
        domain_id: int,
        owner: str,
        thread_name: str,
        parameter_overrides: Sequence[Parameter] = (),
        type_description_service: bool = False,
    ) -> None:
        """Start the node `name` in `domain_id`; `owner` names who it serves in the log."""
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.parameter import Parameter
        from rclpy.signals import SignalHandlerOptions

        from .live_graph import LiveGraphNode

        self.context = rclpy.Context()
        rclpy.init(
            context=self.context,
            domain_id=domain_id,
            signal_handler_options=SignalHandlerOptions.NO,
        )
        self.born = time.monotonic()  # the DDS participant comes with the first node
        self.node: Any = LiveGraphNode(
            name,
            context=self.context,
            start_parameter_services=False,
            parameter_overrides=[
                *parameter_overrides,
                Parameter("start_type_description_service", value=type_description_service),
            ],
        )
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.spin_error: BaseException | None = None  # why the spin thread stopped, if it did
        self.closing = False  # set first when the owner closes: spin errors are expected then
        self._owner = owner
        self._thread = threading.Thread(target=self._spin, name=thread_name, daemon=True)
        self._thread.start()

    def _spin(self) -> None:
        from rclpy.exceptions import InvalidHandle

        while True:
            try:
                self.executor.spin()
                return
            except InvalidHandle:
                # A subscription or timer destroyed from another thread (a plot closed, a
                # recorder stopped) while the executor waited on it: rclpy raises here; the
                # next wait leaves it out, so spin on.
                if self.closing or not self.context.ok():
                    return
                continue
            except Exception as err:
                if self.closing or not self.context.ok():
                    return  # closing: spin ends with the context
                _log.error("%s ROS thread stopped", self._owner, exc_info=err)
                self.spin_error = err  # after the log: who sees the error finds it logged
                return

    def wait_future(self, future: Future, timeout: float) -> Any:
        """Wait for an rclpy future completed by the spin thread; raise TimeoutError."""
        done = threading.Event()
        future.add_done_callback(lambda _f: done.set())
        if not done.wait(timeout):
            future.cancel()
            raise TimeoutError(f"no answer within {timeout:g} s")
        return future.result()

    def close(self) -> None:
        """Tear down in the order that never aborts the interpreter; idempotent."""
        self.closing = True
        with contextlib.suppress(Exception):
            self.executor.shutdown(timeout_sec=2.0)
        self._thread.join(timeout=2.0)
        with contextlib.suppress(Exception):
            self.node.destroy_node()
        with contextlib.suppress(Exception):
            self.context.try_shutdown()


class Session:
    """Own a ROS domain, a spinning client node and the child processes of this kernel."""

    def __init__(self, *, domain_id: int | None = None) -> None:
        reap_orphans()
        # before this kernel's participant: a port segment left unfinished would hang it
        sweep_stale_segments()
        base = _explicit_env()
        if domain_id is not None:
            base[DOMAIN_ENV] = str(domain_id)
        self._lease = lease_domain(base)
        self.domain_id = self._lease.domain_id
        self.env = session_env(self.domain_id, base)
        self._export()
        ament.use_workspace_interfaces()  # messages built in rosject/, such as tf2_msgs
        self._children: list[ChildProcess] = []
        self._lock = threading.Lock()
        self._closed = False
        self._ros = SpinningNode(
            f"_course_client_{os.getpid()}",
            domain_id=self.domain_id,
            owner="the session's",
            thread_name="course-ros-spin",
        )
        self.context, self.node = self._ros.context, self._ros.node
        atexit.register(self.close)

    def __repr__(self) -> str:
        state = "closed" if self._closed else f"{len(self.children)} children"
        return f"<Session domain={self.domain_id} {state}>"

    @property
    def spin_error(self) -> BaseException | None:
        """Why the session's ROS thread stopped, if it did."""
        return self._ros.spin_error

    @property
    def closed(self) -> bool:
        return self._closed

    @property
    def children(self) -> list[ChildProcess]:
        """Return the children that are still running (a restarted one counts again)."""
        with self._lock:
            return [c for c in self._children if c.alive]

    @property
    def every_child(self) -> list[ChildProcess]:
        """Return every child started so far, ended or not (an exercise judges one that ended)."""
        with self._lock:
            return list(self._children)

    def _check_open(self) -> None:
        if self._closed:
            raise SessionClosedError()
        if self.spin_error is not None:
            raise SessionThreadError(self.spin_error)

    def wait_future(self, future: Future, timeout: float) -> Any:
        """Wait for an rclpy future completed by the spin thread; raise TimeoutError."""
        self._check_open()
        return self._ros.wait_future(future, timeout)

    def spawn(
        self,
        argv: Sequence[str],
        *,
        name: str,
        cwd: str | os.PathLike[str] | None = None,
        env_extra: Mapping[str, str] | None = None,
        merge_stderr: bool = False,
    ) -> ChildProcess:
        """Start a child in this session's domain; it dies with the session."""
        self._check_open()
        env = {**self.env, **(env_extra or {})}
        child = spawn(argv, name=name, env=env, cwd=cwd, merge_stderr=merge_stderr)
        with self._lock:
            self._children.append(child)  # kept when it exits: restart() revives the handle
        return child

    def run(
        self,
        package: str,
        executable: str,
        *args: str,
        name: str | None = None,
        cwd: str | os.PathLike[str] | None = None,
    ) -> ChildProcess:
        """Start `executable` of `package` as `ros2 run package executable args...` does."""
        path = ament.find_executable(package, executable, self.env)
        with param_journal.acting_door("lesson.run"):
            where = str(cwd) if cwd else None
            param_journal.record_start(self.domain_id, executable, list(args), cwd=where)
        return self.spawn([str(path), *args], name=name or executable, cwd=cwd)

    def stop_children(self, *, timeout: float = 5.0) -> None:
        """Stop every child like Ctrl-C, all at once (exited ones: what is left of their group)."""
        with self._lock:
            children = list(self._children)
        # plain threads: a pool cannot take work once the interpreter exits (atexit)
        stoppers = [
            threading.Thread(target=c.stop, kwargs={"timeout": timeout}, daemon=True)
            for c in children
        ]
        for stopper in stoppers:
            stopper.start()
        for stopper in stoppers:
            stopper.join()

    def _export(self) -> None:
        """Put this session's domain and workspace in os.environ.

        This process's own participant reads discovery settings from os.environ, and its
        shell commands (`!ros2 ...`) and launch files see the workspace as if sourced.
        """
        overlay = (*isolation_env(0), _PROFILE_ENV, "AMENT_PREFIX_PATH", "COLCON_PREFIX_PATH")
        overlay += tuple(ROS_DISTRO_ENV)
        os.environ.update({k: self.env[k] for k in overlay if k in self.env})
        os.environ[DOMAIN_ENV] = os.environ[SESSION_DOMAIN_ENV] = str(self.domain_id)
        os.environ.pop("ROS_LOCALHOST_ONLY", None)

    def close(self) -> None:
        """Stop the children and tear rclpy down in the order that never aborts; idempotent."""
        if self._closed:
            return
        self._closed = True
        atexit.unregister(self.close)
        self._ros.closing = True
        self.stop_children()
        self._ros.close()
        self._lease.release()
        if os.environ.get(SESSION_DOMAIN_ENV) == str(self.domain_id):
            os.environ.pop(DOMAIN_ENV, None)
            os.environ.pop(SESSION_DOMAIN_ENV, None)
        current = _current  # read without the lock: get_session() closes under it
        if current is not None and current is not self and not current.closed:
            current._export()  # another session of this process was made and closed meanwhile


_current: Session | None = None
_current_lock = threading.Lock()


def get_session(*, domain_id: int | None = None) -> Session:
    """Return this process's session, starting one if there is none or it was closed.

    A session whose ROS thread stopped is reported once (SessionThreadError) and closed, so
    running the lesson's first cell again starts a fresh one.
    """
    global _current
    with _current_lock:
        if _current is not None and _current.spin_error is not None and not _current.closed:
            error = _current.spin_error
            _current.close()
            raise SessionThreadError(error)
        if _current is None or _current.closed:
            _current = Session(domain_id=domain_id)
        return _current


def close_current_session() -> None:
    """Close this process's session, if one is open: its children stop, and the next
    get_session() starts a fresh one in a domain of its own."""
    with _current_lock:
        current = _current
    if current is not None:
        current.close()
