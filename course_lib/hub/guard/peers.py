"""Who is at the other end of a TCP connection: the Unix account whose socket it is, when that
socket is on this host (this network namespace), else its address.

Asked of the kernel through NETLINK_SOCK_DIAG: one socket looked up by its four addresses, a
hash lookup (reading /proc/net/tcp instead walks every connection of the host, each time).
"""

from __future__ import annotations

import contextlib
import errno
import ipaddress
import pwd
import socket
import struct
from dataclasses import dataclass

__all__ = ["Peer", "PeerFinder"]

NETLINK_SOCK_DIAG = 4
SOCK_DIAG_BY_FAMILY = 20
NLM_F_REQUEST = 0x1
NLMSG_ERROR = 0x2
INET_DIAG_NOCOOKIE = 0xFFFFFFFF
_ALL_STATES = 0xFFFFFFFF
_HEADER = struct.Struct("=IHHII")  # nlmsghdr: length, type, flags, sequence, port id
_REQUEST = struct.Struct("=BBBxI")  # inet_diag_req_v2: family, protocol, ext, states
_UID_AT = _HEADER.size + 4 + 48 + 12  # inet_diag_msg: 4 bytes, its sockid, 3 u32, then uid


@dataclass(frozen=True)
class Peer:
    """The other end of a connection: a local account (`uid`) or a remote `address`."""

    uid: int | None = None
    address: str = ""

    def __str__(self) -> str:
        if self.uid is None:
            return f"address {self.address}"
        try:
            return f"account {pwd.getpwuid(self.uid).pw_name!r} (uid {self.uid})"
        except KeyError:
            return f"uid {self.uid}"


def _packed(address: str) -> tuple[int, bytes]:
    """Return the family and the 16 bytes of inet_diag_sockid for `address`."""
    ip = ipaddress.ip_address(address.split("%", 1)[0])
    mapped = getattr(ip, "ipv4_mapped", None)  # ::ffff:127.0.0.1: a v4 connection
    if mapped is not None:
        ip = mapped
    family = socket.AF_INET if ip.version == 4 else socket.AF_INET6
    return family, ip.packed.ljust(16, b"\0")


class PeerFinder:
    """Look up the account of the other end of accepted connections (one netlink socket)."""

    def __init__(self) -> None:
        self._netlink = socket.socket(socket.AF_NETLINK, socket.SOCK_DGRAM, NETLINK_SOCK_DIAG)
        self._netlink.settimeout(1.0)
        self._sequence = 0

    def peer(self, connection: socket.socket) -> Peer:
        """Return who is at the other end of `connection` (accepted, TCP)."""
        remote, local = connection.getpeername(), connection.getsockname()
        uid = self.uid_of(remote[0], remote[1], local[0], local[1])
        return Peer(uid=uid) if uid is not None else Peer(address=remote[0])

    def uid_of(self, address: str, port: int, to_address: str, to_port: int) -> int | None:
        """Return the uid of the socket on this host bound to `address`:`port` and connected
        to `to_address`:`to_port`, or None if there is none here."""
        family, source = _packed(address)
        _, destination = _packed(to_address)
        self._sequence = (self._sequence + 1) & 0xFFFFFFFF
        request = (
            _REQUEST.pack(family, socket.IPPROTO_TCP, 0, _ALL_STATES)
            + struct.pack(">HH", port, to_port)
            + source
            + destination
            + struct.pack("=III", 0, INET_DIAG_NOCOOKIE, INET_DIAG_NOCOOKIE)
        )
        header = _HEADER.pack(
            _HEADER.size + len(request), SOCK_DIAG_BY_FAMILY, NLM_F_REQUEST, self._sequence, 0
        )
        self._netlink.send(header + request)
        while True:
            reply = self._netlink.recv(65536)
            length, kind, _, sequence, _ = _HEADER.unpack_from(reply)
            if sequence != self._sequence:
                continue  # the late answer of an earlier question
            if kind == NLMSG_ERROR:
                code = -struct.unpack_from("=i", reply, _HEADER.size)[0]
                if code in (errno.ENOENT, 0):
                    return None
                raise OSError(code, f"sock_diag lookup: {errno.errorcode.get(code, code)}")
            if kind != SOCK_DIAG_BY_FAMILY or length < _UID_AT + 4:
                return None
            return int(struct.unpack_from("=I", reply, _UID_AT)[0])

    def close(self) -> None:
        with contextlib.suppress(OSError):
            self._netlink.close()
