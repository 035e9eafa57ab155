"""The socket probes: a TCP port nothing on 127.0.0.1 holds right now, a Unix socket that
answers, and who holds the port a connection reached."""

from __future__ import annotations

import ipaddress
import os
import socket

from .procfs import tcp_listeners

__all__ = ["free_port", "held_only_by", "unix_socket_answers"]


def free_port(host: str = "127.0.0.1") -> int:
    """Return a TCP port free on `host` right now (another process may take it after)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind((host, 0))
        return int(probe.getsockname()[1])


def unix_socket_answers(path: str | os.PathLike[str]) -> bool:
    """Return whether a process listens on the Unix socket at `path` (a file that a killed
    server left refuses the connection)."""
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as probe:
        try:
            probe.connect(os.fspath(path))
        except OSError:
            return False
    return True


_Address = ipaddress.IPv4Address | ipaddress.IPv6Address


def _plain(address: _Address) -> _Address:
    mapped = getattr(address, "ipv4_mapped", None)  # ::ffff:127.0.0.1 is 127.0.0.1
    return mapped if mapped is not None else address


def held_only_by(host: str, port: int, uid: int) -> bool:
    """Return whether a connection to `host`:`port` in this thread's network lands on a
    listening socket that `uid` made, and could land on no other account's: the check
    before a secret goes to a port on this host (whoever binds a freed port gets it).

    A socket bound to `host` itself or to every address of its family takes the connection;
    only where none is, an IPv6 wildcard one may (dual-stack: it cannot coexist with those).
    """
    target = _plain(ipaddress.ip_address(host))
    owners: list[int] = []  # the uids of the sockets that would take the connection
    for tables in (("tcp",), ("tcp6",)) if target.version == 4 else (("tcp6",),):
        if owners:  # no other account's socket can share its address and port, dual-stack or not
            break
        listening = [(_plain(a), o) for a, p, o in tcp_listeners(tables) if p == port]
        owners = [
            o
            for a, o in listening
            if a == target or (a.is_unspecified and a.version == target.version)
        ]
        if not owners:
            owners = [o for a, o in listening if a.is_unspecified and a.version == 6]
    return bool(owners) and all(owner == uid for owner in owners)
