"""The proxy's routes to learners' servers: pinned to each server's own socket.

With the wall, a learner's server listens on `<sockets>/<name>/server.sock`, in a folder the
learner owns. The proxy (root) connected by that path, so a learner who put a symbolic link
there to another learner's socket had their requests carried to that server (root follows
links into folders the learner cannot enter), and its pooled connections kept that route after the
link was gone. The hub now routes to a hard link of the socket the learner's server is
listening on, made by root in a folder of its own (`.routes`, 0700) once that socket is
checked: a socket (not a link), owned by the learner, and its listener running as them.
A link the learner makes or removes later changes nothing of the route.
"""

from __future__ import annotations

import os
import socket
import stat
import struct
from pathlib import Path

from ...core.errors import CourseError
from .root_folder import root_only_folder

__all__ = ["ROUTES_FOLDER", "RouteError", "forget_route", "pin_route"]

ROUTES_FOLDER = ".routes"  # in the sockets folder; no account's name starts with a dot


class RouteError(CourseError):
    """A learner's server socket is not one the hub may route to."""


def _routes(sockets: Path) -> Path:
    return root_only_folder(sockets / ROUTES_FOLDER)


def _listener_uid(path: Path) -> int:
    """Return the uid of the process listening on the Unix socket `path` (SO_PEERCRED)."""
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as probe:
        probe.settimeout(5.0)
        probe.connect(str(path))
        credentials = probe.getsockopt(socket.SOL_SOCKET, socket.SO_PEERCRED, 12)
    return struct.unpack("3i", credentials)[1]


def pin_route(server_socket: Path, sockets: Path, name: str, uid: int) -> Path:
    """Return the path the proxy routes `name`'s requests to: a hard link, in the hub's own
    folder, of the socket `server_socket` is now, if it is a socket of `uid` that a process
    of `uid` listens on; else raise RouteError (nothing is routed)."""
    folder = _routes(sockets)
    route = folder / f"{name}.sock"
    making = folder / f".{name}.{os.getpid()}.new"
    making.unlink(missing_ok=True)
    os.link(server_socket, making, follow_symlinks=False)  # a link is linked as a link
    try:
        info = making.lstat()
        if not stat.S_ISSOCK(info.st_mode) or info.st_uid != uid:
            kind = "a link" if stat.S_ISLNK(info.st_mode) else "not a socket of theirs"
            raise RouteError(
                f"{server_socket} is {kind}: {name}'s requests are not routed there.",
                hint=f"{name}'s server is stopped; they start it again from the hub's home page.",
            )
        listener = _listener_uid(making)
        if listener != uid:
            raise RouteError(
                f"{server_socket} is served by uid {listener}, not {name}'s server.",
                hint=f"{name}'s server is stopped; they start it again from the hub's home page.",
            )
        making.replace(route)
    finally:
        making.unlink(missing_ok=True)
    return route


def forget_route(sockets: Path, name: str) -> None:
    """Remove `name`'s route (their server has stopped)."""
    (sockets / ROUTES_FOLDER / f"{name}.sock").unlink(missing_ok=True)
