"""The one reader of /proc: what the kernel says about a process, and the host's sockets.

Standard library only, on purpose, and not psutil (pinned for tests and bench, and used by
`machine/drivers.py` for its process trees):

- `domain.py` reads the UDP table through here, and tests run it as other Unix users with
  the system Python, where the course's packages are not importable;
- the owner tags children carry (``COURSE_OWNER=<pid>:<start time>``) hold field 22 of
  ``/proc/<pid>/stat`` as the kernel writes it, compared as text across processes and
  course versions; psutil only offers it converted to a float of seconds since the epoch
  (through the boot time and clock ticks), which would change every tag;
- the `ros2` terminal command and `make stop` import this at every start: psutil costs about
  15 ms of import (``python -X importtime -c "import psutil"``, measured in the course's venv)
  for what is here a handful of small reads, while this module's own cost is pathlib's.
"""

from __future__ import annotations

import contextlib
import functools
import ipaddress
import os
import sys
from collections.abc import Iterable
from pathlib import Path

__all__ = [
    "PROC",
    "bound_udp_ports",
    "cmdline",
    "environ",
    "fd_targets",
    "has_children",
    "holder_start",
    "network_namespace",
    "owner_uid",
    "parent_pid",
    "pid_alive",
    "pid_max",
    "pid_namespace",
    "pids",
    "start_time",
    "stat_fields",
    "tcp_listeners",
    "udp_ports",
    "udp_socket_inodes",
    "unix_socket_paths",
]

PROC = Path("/proc")
_UDP_TABLES = ("udp", "udp6")
_TCP_LISTEN = "0A"  # the state column of a listening socket


def stat_fields(pid: int) -> list[str] | None:
    """Return the fields of /proc/<pid>/stat after the command name, or None if no such pid.

    Index 0 is the state, 1 the parent pid, 2 the process group, 19 the start time.
    """
    try:  # os-level reads: a third of pathlib's cost, and `%ros2` asks on every command
        fd = os.open(f"{PROC}/{pid}/stat", os.O_RDONLY)
        try:
            raw = os.read(fd, 4096)
        finally:
            os.close(fd)
        return raw.decode(errors="replace").rsplit(")", 1)[1].split()
    except (OSError, IndexError):
        return None


def start_time(pid: int) -> str | None:
    """Return the start time of live process `pid` (field 22 of its stat), or None."""
    fields = stat_fields(pid)
    return None if fields is None or fields[0] in ("Z", "X") else fields[19]


def holder_start(pid: int) -> str | None:
    """Return the start time of whatever process holds `pid`, a zombie too; None if none."""
    fields = stat_fields(pid)
    return None if fields is None else fields[19]


def pid_alive(pid: int) -> bool:
    """Return True while process `pid` runs (a zombie counts as dead)."""
    return start_time(pid) is not None


def parent_pid(pid: int) -> int:
    """Return the parent of process `pid`, or 0 if it is gone."""
    fields = stat_fields(pid)
    return int(fields[1]) if fields is not None else 0


def cmdline(pid: int) -> tuple[str, ...] | None:
    """Return the command line of process `pid` (empty for a kernel thread), None if gone."""
    try:
        raw = (PROC / str(pid) / "cmdline").read_bytes()
    except OSError:
        return None
    return tuple(arg.decode(errors="replace") for arg in raw.split(b"\0") if arg)


def environ(pid: int) -> dict[str, str]:
    """Return the environment of process `pid` ({} if it cannot be read)."""
    try:
        raw = (PROC / str(pid) / "environ").read_bytes()
    except OSError:
        return {}
    pairs = (item.partition(b"=") for item in raw.split(b"\0") if item)
    return {k.decode(errors="replace"): v.decode(errors="replace") for k, _, v in pairs}


def maps_library(pid: int, name: str) -> bool:
    """Return whether process `pid` has a shared library `name` (e.g. "librcl.so") mapped;
    False if it is gone or not ours to read."""
    try:
        with open(PROC / str(pid) / "maps", "rb") as maps:
            needle = b"/" + name.encode()
            return any(needle in line for line in maps)
    except OSError:
        return False


def owner_uid(pid: int) -> int | None:
    """Return the Unix user that owns process `pid`, or None if it is gone."""
    try:
        return (PROC / str(pid)).stat().st_uid
    except OSError:
        return None


def has_children(pid: int) -> bool:
    """Return whether `pid` has a child process now (any of its threads' children)."""
    with contextlib.suppress(OSError):
        for task in PROC.joinpath(str(pid), "task").iterdir():
            if task.joinpath("children").read_text().strip():
                return True
    return False


def pids() -> list[int]:
    """Return the pids of every process this PID namespace shows."""
    return [int(entry.name) for entry in PROC.iterdir() if entry.name.isdigit()]


@functools.cache
def pid_max() -> int:
    """Return the largest pid this host hands out, plus one (/proc/sys/kernel/pid_max)."""
    try:
        return int((PROC / "sys" / "kernel" / "pid_max").read_text())
    except (OSError, ValueError):
        return 4_194_304  # Linux's ceiling on 64-bit machines


@functools.cache
def pid_namespace() -> str:
    """Return the id of this process's PID namespace (pids mean nothing outside it)."""
    try:
        return os.readlink(PROC / "self" / "ns" / "pid").strip("pid:[]")
    except OSError:
        return ""


def network_namespace(pid: int | str = "self") -> str | None:
    """Return the id of the network namespace of `pid` (ports and ROS domains mean nothing
    outside it), or None if it is gone or not ours to read."""
    try:
        return os.readlink(PROC / str(pid) / "ns" / "net")
    except OSError:
        return None


def fd_targets(pid: int) -> list[str]:
    """Return what the open file descriptors of `pid` point to (`socket:[123]`, paths)."""
    targets = []
    with contextlib.suppress(OSError):
        for fd in (PROC / str(pid) / "fd").iterdir():
            with contextlib.suppress(OSError):
                targets.append(os.readlink(fd))
    return targets


def unix_socket_paths() -> dict[str, str]:
    """Return the bound Unix sockets of this network namespace: `socket:[inode]` -> path."""
    found = {}
    with contextlib.suppress(OSError):
        for line in (PROC / "net" / "unix").read_text().splitlines()[1:]:
            parts = line.split(None, 7)
            if len(parts) == 8:
                found[f"socket:[{parts[6]}]"] = parts[7]
    return found


def udp_ports(tables: Iterable[str]) -> set[int]:
    """Return the local ports listed in /proc/net/udp (or udp6) text."""
    ports = set()
    for table in tables:
        for line in table.splitlines()[1:]:
            fields = line.split()
            if len(fields) > 1 and ":" in fields[1]:  # "0100007F:1F90": address, port in hex
                ports.add(int(fields[1].rsplit(":", 1)[1], 16))
    return ports


def bound_udp_ports() -> set[int] | None:
    """Return the local ports of every UDP socket on this host (all users); None without /proc."""
    tables = []
    for name in _UDP_TABLES:
        with contextlib.suppress(OSError):
            tables.append((PROC / "net" / name).read_text())
    return udp_ports(tables) if tables else None


def udp_socket_inodes() -> dict[str, int]:
    """Return the UDP sockets of this network namespace: fd target (`socket:[inode]`) -> port."""
    found = {}
    for name in _UDP_TABLES:
        with contextlib.suppress(OSError):
            for line in (PROC / "net" / name).read_text().splitlines()[1:]:
                fields = line.split()
                if len(fields) > 9 and ":" in fields[1]:
                    found[f"socket:[{fields[9]}]"] = int(fields[1].rsplit(":", 1)[1], 16)
    return found


def _address(text: str) -> ipaddress.IPv4Address | ipaddress.IPv6Address:
    """Return the address of a /proc/net/tcp{,6} entry ("0100007F": each 32-bit word is
    printed in the host's byte order)."""
    raw = bytes.fromhex(text)
    words = [raw[i : i + 4] for i in range(0, len(raw), 4)]
    ordered = b"".join(w[::-1] for w in words) if sys.byteorder == "little" else raw
    return ipaddress.ip_address(ordered)


def tcp_listeners(
    tables: tuple[str, ...] = ("tcp", "tcp6"),
) -> list[tuple[ipaddress.IPv4Address | ipaddress.IPv6Address, int, int]]:
    """Return (address, port, owner uid) of every listening TCP socket in the calling
    thread's network namespace (all users'), from /proc/net's `tables` (each read walks all
    the host's connections: a few ms). The owner is whoever created the socket: a socket
    handed to a child keeps its creator's uid."""
    found = []
    for name in tables:
        with contextlib.suppress(OSError):
            for line in (PROC / "thread-self" / "net" / name).read_text().splitlines()[1:]:
                fields = line.split()
                if len(fields) > 7 and fields[3] == _TCP_LISTEN:
                    address, port = fields[1].rsplit(":", 1)
                    found.append((_address(address), int(port, 16), int(fields[7])))
    return found
