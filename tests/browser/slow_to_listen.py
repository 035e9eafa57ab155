"""A Jupyter server extension for test_lab_server.py: the server listens 2 s after its address.

Jupyter Server prints its address, then binds its port in the first turn of its event loop; a
busy machine can delay that turn. This extension makes the delay certain: its callback, queued
before the bind, blocks the loop for 2 s.
"""

from __future__ import annotations

import time
from typing import Any

DELAY_S = 2.0


def _jupyter_server_extension_points() -> list[dict[str, str]]:
    return [{"module": "slow_to_listen"}]


def _load_jupyter_server_extension(serverapp: Any) -> None:
    serverapp.io_loop.add_callback(time.sleep, DELAY_S)
