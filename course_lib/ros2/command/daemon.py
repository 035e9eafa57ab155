"""A per-domain background process holding a warm client node, serving `ros2` commands.

Like the real `ros2 daemon`, it keeps discovery going between commands, so a terminal
`ros2 param get` costs one socket round trip instead of an rclpy start and a discovery wait.
Its node is named as ros2cli's daemon node (`_ros2cli_daemon_<domain>_<hex>`). It stops on
`ros2 daemon stop`, when its owner (the lab, the shell or the process that started it) is
gone, and after its idle time.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import select
import signal
import socket
import struct
import threading
import time
from collections.abc import Mapping
from typing import Any

from ...core.host.ports import unix_socket_answers
from ...core.param_journal import acting_door
from ...processes.children import ChildProcess, spawn
from ...processes.orphans import OWNER_ENV, owner_alive
from ...processes.ownership import LAB_ENV
from ..node.connect import IDLE_ENV, SHUTDOWN, daemon_argv, daemon_lock, daemon_socket
from ..verbkit.console import StreamingConsole
from .commands import Context, execute

__all__ = ["serve", "start_daemon"]

_ACCEPT_TICK_S = 0.5  # how soon the daemon notices that its owner is gone
_CLAIM_WAIT_S = 10.0  # how long a new daemon waits for a stopping one to exit
STAGING_SUFFIX = ".new"  # the socket's name until it listens (fits SOCKET_NAME_MAX)


def start_daemon(env: Mapping[str, str]) -> ChildProcess:
    """Start the daemon for env's ROS_DOMAIN_ID as a child owned by this process."""
    if not env.get("ROS_DOMAIN_ID"):
        raise ValueError("start_daemon needs ROS_DOMAIN_ID in env (the course's domain)")
    return spawn(daemon_argv(), name=f"ros2-daemon-{env['ROS_DOMAIN_ID']}", env=env)


class _Connection:
    """One client connection: a command in, framed output back, cancel on hang-up."""

    def __init__(
        self, sock: socket.socket, client_factory: Any, stop: threading.Event, server: Any
    ) -> None:
        self.sock = sock
        self.client_factory = client_factory
        self.stop = stop
        self.server = server
        self.lock = threading.Lock()

    def wake(self) -> None:
        """Wake the server's accept() so that it sees the stop request at once."""
        with contextlib.suppress(OSError):
            self.server.shutdown(socket.SHUT_RDWR)

    def send(self, frame: dict[str, Any]) -> None:
        data = json.dumps(frame).encode() + b"\n"
        with self.lock:
            self.sock.sendall(data)

    def watch_hang_up(self, console: StreamingConsole) -> None:
        with contextlib.suppress(OSError):
            while self.sock.recv(1024):
                pass
        console.cancelled.set()

    def handle(self) -> None:
        with contextlib.suppress(OSError, ValueError), self.sock:
            line = self.sock.makefile("r", encoding="utf-8").readline()
            request = json.loads(line)
            if request.get("control") == SHUTDOWN:
                self.send({"pid": os.getpid()})
                self.stop.set()
                self.wake()
                return

            def write(stream: str, text: str) -> None:
                try:
                    self.send({"o" if stream == "stdout" else "e": text})
                except OSError:
                    console.cancelled.set()

            console = StreamingConsole(write, width=int(request.get("width", 80)))
            threading.Thread(target=self.watch_hang_up, args=(console,), daemon=True).start()
            env = _terminal_env(request.get("env"))
            ctx = Context(console, self.client_factory, cwd=request.get("cwd"), env=env)
            with acting_door("terminal"):  # only the terminal's `ros2` asks the daemon
                code = execute(list(request["argv"]), ctx)
            self.send({"exit": code})


def _terminal_env(sent: Any) -> dict[str, str]:
    """Return the environment a terminal's command runs with, as the terminal would make it.

    The verbs that read the ament index (pkg, interface) see the terminal's
    AMENT_PREFIX_PATH (a workspace it sourced) with the course's workspace underlaid; the
    graph verbs use the daemon's own node. A client that sent no environment gets none.
    """
    if not isinstance(sent, dict):
        return {}
    from ...session.session import session_env

    env = {str(k): str(v) for k, v in sent.items()}
    return session_env(int(os.environ.get("ROS_DOMAIN_ID") or 0), env)


def same_user(conn: socket.socket) -> bool:
    """Return whether the peer of a Unix connection runs as this process's user.

    The socket is private (mode 600 in a private folder); this is the second lock: a
    connection from another user (a folder opened by mistake, a shared /tmp) is closed
    before a byte of it is read.
    """
    try:
        creds = conn.getsockopt(socket.SOL_SOCKET, socket.SO_PEERCRED, struct.calcsize("3i"))
    except OSError:
        return False
    _pid, uid, _gid = struct.unpack("3i", creds)
    return uid == os.getuid()


def _claim(domain: int) -> socket.socket | None:
    """Bind the domain's socket, holding its lock for life; None if a daemon serves it.

    A daemon that is shutting down still holds the lock: wait for it to go.
    """
    path = daemon_socket(domain)
    fd = os.open(daemon_lock(domain), os.O_RDWR | os.O_CREAT, 0o600)  # inherited by no one
    deadline = time.monotonic() + _CLAIM_WAIT_S
    while True:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            break
        except BlockingIOError:
            if unix_socket_answers(path) or time.monotonic() >= deadline:
                os.close(fd)
                return None
            time.sleep(0.02)
    # Bound under another name and renamed once it listens: the socket's path exists only
    # while a connection to it is accepted, so its presence means "ready" to every client
    # (a connection between bind and listen is refused). The rename replaces a killed
    # daemon's leftover socket.
    staging = path + STAGING_SUFFIX
    with contextlib.suppress(FileNotFoundError):
        os.unlink(staging)
    server = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    server.bind(staging)
    os.chmod(staging, 0o600)
    server.listen(16)
    os.replace(staging, path)
    return server


def _watch(owner: str | None) -> int | None:
    """Return a pidfd that becomes readable when the owner exits (None: poll instead)."""
    pid = owner.partition(":")[0] if owner else ""
    if not pid.isdigit() or not hasattr(os, "pidfd_open"):
        return None
    try:
        fd = os.pidfd_open(int(pid))
    except OSError:
        return None
    if not owner or not owner_alive(owner):  # the pid was reused before we opened it
        os.close(fd)
        return None
    return fd


def _serve_forever(
    server: socket.socket,
    client: Any,
    *,
    idle_s: float | None,
    owner: str | None,
    stop: threading.Event,
) -> None:
    server.setblocking(False)
    watch = _watch(owner)
    waited = [server] + ([watch] if watch is not None else [])
    last = time.monotonic()
    try:
        while not stop.is_set() and (not owner or owner_alive(owner)):
            if idle_s is not None and time.monotonic() - last >= idle_s:
                return
            ready, _, _ = select.select(waited, [], [], _ACCEPT_TICK_S)
            if watch is not None and watch in ready:
                return  # the owner exited: the lab, shell or process we belong to
            if server not in ready:
                continue
            try:
                conn, _ = server.accept()
            except BlockingIOError:
                continue
            except OSError:
                return  # woken by a shutdown request
            if not same_user(conn):
                conn.close()
                continue
            conn.setblocking(True)
            last = time.monotonic()
            handler = _Connection(conn, lambda: client, stop, server)
            threading.Thread(target=handler.handle, daemon=True).start()
    finally:
        if watch is not None:
            os.close(watch)


def _journal_parameter_events(node: Any, domain: int) -> Any:
    """Journal every /parameter_events message of a lab's domain, as its kernels do: a change
    made while no kernel of the lab listens (a node's own, a terminal's) is traced too, and
    `lesson.history` counts an event that several listeners journaled once."""
    from rcl_interfaces.msg import ParameterEvent
    from rclpy.qos import qos_profile_parameter_events

    from ...core import param_journal
    from ...session.quiet_events import quiet_subscription
    from ..values import event_record

    def journal(msg: Any) -> None:
        record = event_record(msg)
        if record is not None:
            param_journal.append(domain, record)

    return node.create_subscription(
        ParameterEvent,
        "/parameter_events",
        journal,
        qos_profile_parameter_events,
        event_callbacks=quiet_subscription(),
    )


def serve(*, idle_s: float | None = None) -> int:
    """Serve commands for this process's ROS_DOMAIN_ID until stopped, orphaned or idle."""
    from ..node.direct import DirectNode, daemon_node_name

    stop = threading.Event()
    if threading.current_thread() is threading.main_thread():
        # Ctrl-C stops it cleanly, even when started in the background (SIGINT ignored there).
        signal.signal(signal.SIGINT, lambda *_: stop.set())
    domain = int(os.environ.get("ROS_DOMAIN_ID") or 0)
    server = _claim(domain)
    if server is None:
        return 0
    path = daemon_socket(domain)
    try:
        direct = DirectNode(
            domain_id=domain, node_name=daemon_node_name(domain), type_description_service=False
        )
    except BaseException:
        server.close()
        os.unlink(path)
        raise
    try:
        if os.environ.get(LAB_ENV) == "1":
            _journal_parameter_events(direct.node, domain)
        owner = os.environ.get(OWNER_ENV)
        _serve_forever(server, direct.client(), idle_s=idle_s, owner=owner, stop=stop)
    finally:
        server.close()  # new commands now find no daemon; the lock is held until exit
        with contextlib.suppress(FileNotFoundError):
            os.unlink(path)
        direct.close()
    return 0


if __name__ == "__main__":
    idle = os.environ.get(IDLE_ENV)
    raise SystemExit(serve(idle_s=float(idle) if idle else None))
