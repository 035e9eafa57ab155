"""Give each course session a ROS domain of its own, so sessions on one host never meet.

A domain is leased by holding an exclusive ``flock`` on ``domain-<id>.lock`` in the user's
runtime folder; the kernel releases it when the holder exits, however it exits. Children
inherit the id through ``ROS_DOMAIN_ID`` and need no lock of their own.
"""

from __future__ import annotations

import fcntl
import os
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field

from .errors import DomainUnavailableError
from .paths import runtime_dir

__all__ = ["DOMAIN_ENV", "DomainLease", "candidate_domains", "isolation_env", "lease_domain"]

DOMAIN_ENV = "ROS_DOMAIN_ID"
# Domains whose ports Linux allows (0-101 and 215-232); 0 is left to plain ROS users.
_USABLE = [*range(1, 102), *range(215, 233)]


def candidate_domains(start: int) -> Iterator[int]:
    """Yield every usable domain id once, beginning at the one at or after `start`."""
    first = next((i for i, d in enumerate(_USABLE) if d >= start), 0)
    yield from _USABLE[first:] + _USABLE[:first]


@dataclass
class DomainLease:
    """A domain id held by this process until `release()` or exit."""

    domain_id: int
    _fd: int | None = field(default=None, repr=False)

    @property
    def is_locked(self) -> bool:
        return self._fd is not None

    def release(self) -> None:
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None


def _try_lock(domain_id: int) -> int | None:
    path = runtime_dir() / f"domain-{domain_id}.lock"
    fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o600)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        os.close(fd)
        return None
    os.ftruncate(fd, 0)
    os.write(fd, f"{os.getpid()}\n".encode())
    return fd


def lease_domain(env: Mapping[str, str] | None = None) -> DomainLease:
    """Return the domain to use: an explicit ``ROS_DOMAIN_ID`` as is, else a free locked one."""
    env = os.environ if env is None else env
    explicit = env.get(DOMAIN_ENV, "").strip()
    if explicit:
        return DomainLease(int(explicit))
    # Start from a pid-derived id so parallel sessions rarely race for the same lock.
    for domain_id in candidate_domains(1 + os.getpid() % 101):
        fd = _try_lock(domain_id)
        if fd is not None:
            return DomainLease(domain_id, fd)
    raise DomainUnavailableError(
        "Every ROS domain id on this host is taken by other course sessions.",
        hint="close notebooks you no longer use (`make stop` ends them all), then retry.",
    )


def isolation_env(domain_id: int) -> dict[str, str]:
    """Return the variables that keep a session's processes in their own localhost domain."""
    return {
        DOMAIN_ENV: str(domain_id),
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
        "ROS_STATIC_PEERS": "",
    }
