"""The domain wall: each learner's server in a network of its own, with only loopback up.

On one host, ROS 2 discovery on localhost reaches every account that sets the same
`ROS_DOMAIN_ID`, and a TCP port on 127.0.0.1 answers every account. So the hub starts each
learner's server (and so every kernel, terminal, node, 3D view and turtlesim window of their
lab) in a network namespace of its own, where `lo` is the only interface: nothing of the lab
is reachable from the host's network, and nothing in it reaches the host's, except what the
hub relays (below). The same start gives the lab a mount namespace with a private `/dev/shm`,
since Fast DDS's shared-memory transport would otherwise meet other accounts' segments there.

The way in and out, all owned by the hub (root):

- the proxy reaches the server on a Unix socket in a folder only the learner and root can
  enter (`jupyterhub-singleuser --ServerApp.sock`, proxied as `http+unix://`);
- the server and its kernels reach the hub's API and the progress service at their usual
  addresses, 127.0.0.1:<port>, where the hub listens *inside* the learner's namespace and
  relays each connection to the same port on the host, if the hub's account holds it there
  (what a lab sends carries its token: a port freed and taken by another account gets none).

Python 3.11 has no `os.unshare`/`os.setns`: both are called through libc.
"""

from __future__ import annotations

import asyncio
import contextlib
import ctypes
import ctypes.util
import errno
import fcntl
import os
import socket
import struct
import threading
from collections.abc import Awaitable, Callable

from ...core.host.ports import held_only_by

__all__ = [
    "Relay",
    "enter_own_network",
    "listen_in_network_of",
    "wall_problem",
]

CLONE_NEWNS = 0x00020000
CLONE_NEWNET = 0x40000000
_MS_NOSUID, _MS_NODEV, _MS_REC, _MS_SLAVE = 0x2, 0x4, 0x4000, 0x80000
_SIOCGIFFLAGS, _SIOCSIFFLAGS, _IFF_UP = 0x8913, 0x8914, 0x1

_LIBC = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)


def _check(result: int, what: str) -> None:
    if result != 0:
        code = ctypes.get_errno()
        raise OSError(code, f"{what}: {os.strerror(code)}")


def _loopback_up() -> None:
    """Bring `lo` up in the current network namespace (a new one has it down)."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sock:
        request = struct.pack("16sh14x", b"lo", 0)
        flags = struct.unpack("16sh14x", fcntl.ioctl(sock, _SIOCGIFFLAGS, request))[1]
        fcntl.ioctl(sock, _SIOCSIFFLAGS, struct.pack("16sh14x", b"lo", flags | _IFF_UP))


def enter_own_network() -> None:
    """Move this process into a new network namespace (loopback only, up) and a new mount
    namespace with a private /dev/shm. Needs root; safe in a preexec_fn (before setuid)."""
    _check(_LIBC.unshare(CLONE_NEWNET | CLONE_NEWNS), "unshare(CLONE_NEWNET | CLONE_NEWNS)")
    # the host's later mounts still reach this namespace; none of this one's go back
    _check(_LIBC.mount(None, b"/", None, _MS_REC | _MS_SLAVE, None), "mount --make-rslave /")
    if os.path.isdir("/dev/shm"):
        _check(
            _LIBC.mount(b"tmpfs", b"/dev/shm", b"tmpfs", _MS_NOSUID | _MS_NODEV, b"mode=1777"),
            "mount a private /dev/shm",
        )
    _loopback_up()


def wall_problem() -> str | None:
    """Return why this host cannot give a learner a network of their own, or None if it can.

    Tried in a child process, which exits at once, so nothing of this process changes.
    """
    if os.geteuid() != 0:
        return "not root"
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: try, report in one line, exit without Python's clean-up
        os.close(read)
        message = b""
        try:
            enter_own_network()
        except Exception as err:  # anything at all: the parent reports it
            message = str(err).encode()[:500] or b"failed"
        os.write(write, message)
        os._exit(0)
    os.close(write)
    with os.fdopen(read, "rb") as pipe:
        reported = pipe.read().decode(errors="replace")
    os.waitpid(pid, 0)
    return reported or None


def listen_in_network_of(pid: int, port: int) -> socket.socket:
    """Return a TCP socket listening on 127.0.0.1:`port` in process `pid`'s network namespace.

    Made on a thread of its own that joins that namespace and ends: this process's other
    threads stay in the host's network. Needs root (CAP_SYS_ADMIN).
    """
    made: list[socket.socket | BaseException] = []

    def make() -> None:
        try:
            fd = os.open(f"/proc/{pid}/ns/net", os.O_RDONLY | os.O_CLOEXEC)
            try:
                _check(_LIBC.setns(fd, CLONE_NEWNET), "setns(CLONE_NEWNET)")
            finally:
                os.close(fd)
            sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            sock.bind(("127.0.0.1", port))
            sock.listen(64)
            sock.setblocking(False)
            made.append(sock)
        except BaseException as err:  # handed to the caller's thread
            made.append(err)

    thread = threading.Thread(target=make, name=f"wall-listen-{pid}-{port}")
    thread.start()
    thread.join()
    if isinstance(made[0], BaseException):
        raise made[0]
    return made[0]


async def _pipe(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
    try:
        while data := await reader.read(65536):
            writer.write(data)
            await writer.drain()
    except (ConnectionError, OSError):
        pass
    finally:
        with contextlib.suppress(OSError, RuntimeError):  # already closed, or its loop is
            writer.close()


class Relay:
    """Connections to 127.0.0.1:port inside a learner's namespace, carried to 127.0.0.1:port
    on the host (the hub's API, the progress service), for as long as the server runs, when
    the socket listening there is the hub's account's (`holder`, this process's uid)."""

    def __init__(
        self, pid: int, ports: list[int], log: Callable[[str], None], holder: int | None = None
    ) -> None:
        self.pid, self.ports, self._log = pid, ports, log
        self.holder = os.getuid() if holder is None else holder
        self._servers: list[asyncio.base_events.Server] = []

    async def start(self) -> None:
        for port in self.ports:
            listener = listen_in_network_of(self.pid, port)
            handler = self._handler(port)
            self._servers.append(await asyncio.start_server(handler, sock=listener))

    def _handler(
        self, port: int
    ) -> Callable[[asyncio.StreamReader, asyncio.StreamWriter], Awaitable[None]]:
        async def carry(inner_r: asyncio.StreamReader, inner_w: asyncio.StreamWriter) -> None:
            try:
                outer_r, outer_w = await asyncio.open_connection("127.0.0.1", port)
            except OSError as err:
                if err.errno != errno.ECONNREFUSED:
                    self._log(f"relay to 127.0.0.1:{port} failed: {err}")
                inner_w.close()
                return
            if not held_only_by("127.0.0.1", port, self.holder):  # connected: no race
                self._log(
                    f"relay to 127.0.0.1:{port} refused: another account than the hub's holds "
                    f"that port now; nothing of the lab of process {self.pid} went there"
                )
                outer_w.close()
                inner_w.close()
                return
            await asyncio.gather(_pipe(inner_r, outer_w), _pipe(outer_r, inner_w))

        return carry

    def close(self) -> None:
        for server in self._servers:
            server.close()
        self._servers.clear()
