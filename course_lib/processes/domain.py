"""Give each course session a ROS domain of its own, so sessions on one host never meet.

A domain is leased only if no other process on this host uses it:

- the lease itself is a TCP socket bound (never listening) on 127.0.0.1 to a port inside the
  domain's DDS port block that DDS leaves alone. Binding is atomic and works across Unix users
  without a shared folder; the kernel frees the port when the holder exits, however it exits.
- a domain in which any UDP socket is bound in the DDS port block (another ROS 2 program, a
  course session of another clone, anything) is skipped: `/proc/net/udp` lists every socket
  of the host's network namespace, whoever owns it, without root.

Children inherit the id through ``ROS_DOMAIN_ID`` and need no lease of their own. This module
needs only the standard library (tests run it as other Unix users with the system Python),
and so does `core.host.procfs`, which reads the UDP tables for it.
"""

from __future__ import annotations

import errno
import os
import socket
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field

from ..core.errors import DomainUnavailableError
from ..core.host import procfs

__all__ = [
    "DOMAIN_ENV",
    "DomainLease",
    "candidate_domains",
    "domain_in_use",
    "isolation_env",
    "lease_domain",
    "lease_port",
    "port_block",
]

DOMAIN_ENV = "ROS_DOMAIN_ID"
# Domains whose ports Linux allows (0-101 and 215-232); 0 is left to plain ROS users.
_USABLE = [*range(1, 102), *range(215, 233)]
# RTPS port mapping (Fast DDS defaults): domain d uses UDP ports 7400 + 250 d + offset, with
# offsets 0 and 1 (multicast) and 10 + 2 i, 11 + 2 i (participant i). Offset 2 is no DDS port,
# and the lease is TCP anyway, whose port space is separate from UDP's.
_PORT_BASE, _DOMAIN_GAIN, _LEASE_OFFSET = 7400, 250, 2


def candidate_domains(start: int) -> Iterator[int]:
    """Yield every usable domain id once, beginning at the one at or after `start`."""
    first = next((i for i, d in enumerate(_USABLE) if d >= start), 0)
    yield from _USABLE[first:] + _USABLE[:first]


def port_block(domain_id: int) -> range:
    """Return the UDP ports that DDS participants of `domain_id` bind."""
    low = _PORT_BASE + _DOMAIN_GAIN * domain_id
    return range(low, min(low + _DOMAIN_GAIN, 65536))  # domain 232's block ends at 65535


def lease_port(domain_id: int) -> int:
    """Return the TCP port on 127.0.0.1 whose binding leases `domain_id`."""
    return port_block(domain_id).start + _LEASE_OFFSET


def domain_in_use(domain_id: int, bound: set[int] | None = None) -> bool:
    """Return True if some process on this host has a DDS socket in `domain_id`'s ports."""
    bound = (procfs.bound_udp_ports() or set()) if bound is None else bound
    block = port_block(domain_id)
    return any(port in block for port in bound)


@dataclass
class DomainLease:
    """A domain id held by this process until `release()` or exit."""

    domain_id: int
    _sock: socket.socket | None = field(default=None, repr=False)

    @property
    def is_locked(self) -> bool:
        return self._sock is not None

    def release(self) -> None:
        if self._sock is not None:
            self._sock.close()
            self._sock = None


def _try_bind(domain_id: int) -> socket.socket | None:
    """Bind the domain's lease port; None if another process (any user) holds it."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)  # not inherited by children
    try:
        sock.bind(("127.0.0.1", lease_port(domain_id)))
    except OSError as exc:
        sock.close()
        if exc.errno in (errno.EADDRINUSE, errno.EACCES):
            return None
        raise
    return sock


def lease_domain(env: Mapping[str, str] | None = None, *, start: int | None = None) -> DomainLease:
    """Return the domain to use: an explicit ``ROS_DOMAIN_ID`` as is, else a free leased one.

    Args:
        env: the environment to read ``ROS_DOMAIN_ID`` from (default: this process's).
        start: the first domain id to try (default: one derived from the pid, so parallel
            sessions rarely try the same ids in the same order).
    """
    env = os.environ if env is None else env
    explicit = env.get(DOMAIN_ENV, "").strip()
    if explicit:
        return DomainLease(int(explicit))
    bound = procfs.bound_udp_ports() or set()
    first = 1 + os.getpid() % 101 if start is None else start
    for domain_id in candidate_domains(first):
        if domain_in_use(domain_id, bound):
            continue
        sock = _try_bind(domain_id)
        if sock is not None:
            return DomainLease(domain_id, sock)
    raise DomainUnavailableError(
        "Every ROS domain id on this host is in use, by course sessions of any user or by "
        "other ROS 2 programs.",
        hint="close notebooks you no longer use (`make stop` ends this user's), then retry.",
    )


def isolation_env(domain_id: int) -> dict[str, str]:
    """Return the variables that keep a session's processes in their own localhost domain."""
    return {
        DOMAIN_ENV: str(domain_id),
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
        "ROS_STATIC_PEERS": "",
    }
