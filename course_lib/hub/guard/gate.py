"""The hub's TCP ports, held by its launcher from start to stop, each a door to a Unix socket
only root reaches (the proxy, JupyterHub's API, the progress service).

Every connection through a door is counted against the account that opened it (or its
address, from another host: course_lib.hub.guard.peers): past the limit it is reset at once,
and the refusals are said in a few lines every REPORT_EVERY_S. A connection that sends nothing
within FIRST_BYTES_S is closed before it reaches anything behind the door; one whose far end
has finished is closed HALF_OPEN_S later. So no account can hold the hub's files open: two
processes of one account held 20,000 idle connections to JupyterHub's port, which ran out of
file descriptors and wrote 710k lines a minute, and no learner could sign in.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import resource
import socket
import struct
import threading
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass

from .admission import Admission
from .peers import Peer, PeerFinder

__all__ = ["Door", "Gate", "open_files_limit", "unix_listener"]

FIRST_BYTES_S = 20.0  # a browser's unused preconnection lasts about 10 s
HALF_OPEN_S = 30.0
REPORT_EVERY_S = 10.0
FILES_KEPT = 256  # of the open-file limit, for all but the doors' connections (2 files each)
BACKLOG = 512
_CHUNK = 65536


@dataclass(frozen=True)
class Door:
    """A listening TCP socket, what it leads to (a Unix socket's path) and its name."""

    listener: socket.socket
    target: str
    name: str


def open_files_limit() -> int:
    """Raise this process's soft limit of open files to its hard limit (its children inherit
    it); return it."""
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    if hard != resource.RLIM_INFINITY and soft < hard:
        resource.setrlimit(resource.RLIMIT_NOFILE, (hard, hard))
        soft = hard
    return soft


def unix_listener(path: str) -> socket.socket:
    """Return a Unix socket listening at `path` (a stale file there is replaced)."""
    with contextlib.suppress(FileNotFoundError):
        os.unlink(path)
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    listener.bind(path)
    listener.listen(BACKLOG)
    return listener


def _reset(connection: socket.socket) -> None:
    """Close `connection` with a reset: nothing of it lingers on either side."""
    with contextlib.suppress(OSError):
        connection.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
    connection.close()


async def _pipe(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
    """Copy `reader` to `writer` until its end, which `writer` then passes on."""
    with contextlib.suppress(OSError):
        while data := await reader.read(_CHUNK):
            writer.write(data)
            await writer.drain()
        if writer.can_write_eof():
            writer.write_eof()


async def _close(writers: list[asyncio.StreamWriter]) -> None:
    """Close `writers` once what they hold is sent, or HALF_OPEN_S later at the latest."""
    for writer in writers:
        writer.close()
    try:
        closing = asyncio.gather(*(w.wait_closed() for w in writers), return_exceptions=True)
        await asyncio.wait_for(closing, HALF_OPEN_S)
    except (TimeoutError, OSError):
        pass
    finally:
        for writer in writers:
            writer.transport.abort()


class Gate:
    """The doors, served on an event loop in a thread of its own (`start`, `stop`): each
    account or remote address holds at most `per_peer` connections through all of them."""

    def __init__(self, doors: list[Door], *, per_peer: int, log: Callable[[str], None]) -> None:
        self.doors, self._log = doors, log
        total = max(64, (open_files_limit() - FILES_KEPT) // 2)
        self.admission = Admission(per_peer, total)
        try:
            self._finder: PeerFinder | None = PeerFinder()
        except OSError:  # a sandbox without netlink
            self._finder = None
        self._trouble: Counter[str] = Counter()
        self._loop: asyncio.AbstractEventLoop | None = None
        self._stopping: asyncio.Event | None = None
        self._ready = threading.Event()
        self._tasks: set[asyncio.Task[None]] = set()  # the loop keeps only weak references
        self._thread = threading.Thread(
            target=lambda: asyncio.run(self._serve()), name="hub-gate", daemon=True
        )
        if not self._tells_accounts_apart():
            if self._finder is not None:
                self._finder.close()
            self._finder = None
            log(
                "The hub cannot tell which account opens a connection (this kernel answers no "
                "sock_diag lookup: `modprobe tcp_diag`); connections are counted per address."
            )

    def _tells_accounts_apart(self) -> bool:
        probe = socket.create_server(("127.0.0.1", 0))
        with probe, socket.create_connection(probe.getsockname()):
            accepted, _ = probe.accept()
            with accepted:
                return self._peer(accepted) == Peer(uid=os.geteuid())

    def start(self) -> None:
        for door in self.doors:
            door.listener.setblocking(False)
        self._thread.start()
        self._ready.wait(10.0)

    def stop(self) -> None:
        """Close every connection and stop serving (the listeners stay the caller's)."""
        if self._loop is not None and self._stopping is not None:
            with contextlib.suppress(RuntimeError):  # its loop has ended already
                self._loop.call_soon_threadsafe(self._stopping.set)
        self._thread.join(10.0)
        if self._finder is not None:
            self._finder.close()

    async def _serve(self) -> None:
        self._loop, self._stopping = asyncio.get_running_loop(), asyncio.Event()
        for door in self.doors:
            self._loop.add_reader(door.listener, self._accept, door)
        tasks = [asyncio.create_task(self._report())]
        self._ready.set()
        await self._stopping.wait()
        for door in self.doors:
            self._loop.remove_reader(door.listener)
        for task in asyncio.all_tasks() - {asyncio.current_task()}:
            task.cancel()
        await asyncio.gather(*tasks, return_exceptions=True)

    async def _report(self) -> None:
        while True:
            await asyncio.sleep(REPORT_EVERY_S)
            lines = self.admission.report("The hub", REPORT_EVERY_S)
            lines += [f"{what} ({count} times in {REPORT_EVERY_S:.0f} s)."
                      for what, count in self._trouble.items()]  # fmt: skip
            self._trouble.clear()
            for line in lines:
                self._log(line)

    def _peer(self, connection: socket.socket) -> Peer:
        try:
            if self._finder is not None:
                return self._finder.peer(connection)
            return Peer(address=connection.getpeername()[0])
        except OSError:
            return Peer(address="unknown")

    def _accept(self, door: Door) -> None:
        """Take what waits at `door` (a flood's thousands, one after the other)."""
        for _ in range(BACKLOG):
            try:
                connection, _ = door.listener.accept()
            except BlockingIOError:
                return
            except OSError as error:  # out of files, most likely: the next try waits a bit
                self._trouble[f"{door.name} could not accept a connection: {error.strerror}"] += 1
                loop = asyncio.get_running_loop()
                loop.remove_reader(door.listener)
                loop.call_later(0.1, loop.add_reader, door.listener, self._accept, door)
                return
            peer = self._peer(connection)
            if not self.admission.admit(peer):
                _reset(connection)
                continue
            task = asyncio.create_task(self._carry(connection, door, peer))
            self._tasks.add(task)
            task.add_done_callback(self._tasks.discard)

    async def _carry(self, connection: socket.socket, door: Door, peer: Peer) -> None:
        writers: list[asyncio.StreamWriter] = []
        try:
            reader, writer = await asyncio.open_connection(sock=connection)
            writers.append(writer)
            with contextlib.suppress(TimeoutError, OSError):
                first = await asyncio.wait_for(reader.read(_CHUNK), FIRST_BYTES_S)
                if not first:
                    return
                try:
                    inner_reader, inner = await asyncio.open_unix_connection(door.target)
                except (FileNotFoundError, ConnectionRefusedError):
                    return  # not started yet, or starting again: JupyterHub says so
                except OSError as error:
                    self._trouble[f"{door.name} could not reach {door.target}: {error}"] += 1
                    return
                writers.append(inner)
                inner.write(first)
                await self._both_ways(reader, writer, inner_reader, inner)
        finally:
            if writers:
                await _close(writers)
            else:
                connection.close()
            self.admission.release(peer)

    async def _both_ways(
        self,
        reader: asyncio.StreamReader,
        writer: asyncio.StreamWriter,
        inner_reader: asyncio.StreamReader,
        inner: asyncio.StreamWriter,
    ) -> None:
        """Carry both ways until both ends are done, or one is and the other lingers."""
        ways = {
            asyncio.create_task(_pipe(reader, inner)),
            asyncio.create_task(_pipe(inner_reader, writer)),
        }
        try:
            _, lingering = await asyncio.wait(ways, return_when=asyncio.FIRST_COMPLETED)
            if lingering:
                await asyncio.wait(lingering, timeout=HALF_OPEN_S)
        finally:
            for way in ways:
                way.cancel()
