"""The bridge between a page and its kernel in the course's Jupyter servers: jupyter_server's
own, less two ways one websocket message cost the server gigabytes it never gave back.

A message in the old ("legacy") binary format starts with its number of parts, and
jupyter_server unpacks that many offsets with a `struct` format it builds on the spot, which
`struct` then keeps in its cache. A header of `06 00 00 00` (a message in the current
protocol, v1, read as a legacy one) asks for 100,663,296 offsets: one 64-byte message took a
server from 77 MiB to 3,342 MiB, measured here, and the server closed that socket. A `make
chaos` walk left a lab server at 3.4 GB: 3,072 MiB in one cached `struct`, exactly what a v1
message read as legacy asks for. jupyter_server reads the protocol from the socket at each
message and answers legacy once tornado has let go of it; how a v1 socket got there in the walk
(a page reloaded, the lab stopped 10 s) was not reproduced alone.

So the protocol a socket chose is remembered, and a legacy binary message whose header does
not fit the message is refused (a warning in the server's log) instead of unpacked.
"""

from __future__ import annotations

from typing import Any

from jupyter_server.services.kernels.connection.channels import ZMQChannelsWebsocketConnection

__all__ = ["V1_PROTOCOL", "CourseKernelConnection", "legacy_header_fits"]

V1_PROTOCOL = "v1.kernel.websocket.jupyter.org"


def legacy_header_fits(message: bytes) -> bool:
    """Return whether a legacy binary message's header fits it: a big-endian 32-bit number of
    parts n > 0, then n 32-bit offsets, all within the message."""
    if len(message) < 4:
        return False
    parts = int.from_bytes(message[:4], "big", signed=True)
    return parts > 0 and 4 * (parts + 1) <= len(message)


class CourseKernelConnection(ZMQChannelsWebsocketConnection):
    """jupyter_server's kernel websocket connection, safe from ill-sized legacy headers."""

    chosen_protocol: str | None = None  # the socket's protocol, once it chose v1

    @property
    def subprotocol(self) -> str | None:
        """The protocol the socket chose, also once it has closed (None: legacy)."""
        if self.chosen_protocol is None:
            handler = self.websocket_handler
            socket = handler.ws_connection if handler is not None else None
            if socket is not None:
                self.chosen_protocol = socket.selected_subprotocol
        return self.chosen_protocol

    def connect(self) -> Any:
        """Connect the socket to its kernel, the socket's protocol noted first (its handshake
        is done: the page's messages come only after this)."""
        _ = self.subprotocol
        return super().connect()

    def handle_incoming_message(self, incoming_msg: Any) -> None:
        """Pass a page's message on to the kernel, unless it is a legacy binary one whose
        header does not fit it."""
        binary = isinstance(incoming_msg, bytes | bytearray)
        if binary and self.subprotocol != V1_PROTOCOL and not legacy_header_fits(incoming_msg):
            self.log.warning(
                "Refused a %d-byte binary kernel message whose header does not fit it",
                len(incoming_msg),
            )
            return
        super().handle_incoming_message(incoming_msg)
