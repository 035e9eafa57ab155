"""What a running `ros2` verb may use: its console, a ROS client made on first use, cwd/env."""

from __future__ import annotations

import argparse
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from ..node.discovery import requested_spin_time
from .console import Console

__all__ = ["Context", "SimTimeUnavailable", "settled_client"]


@dataclass
class Context:
    """What a verb may use: the console, a ROS client made on first use, the caller's cwd/env."""

    console: Console
    client_factory: Callable[[], Any] | None = None
    cwd: str | None = None
    env: Mapping[str, str] = field(default_factory=dict)
    background_run: Callable[..., Any] | None = None
    _client: Any = None

    @property
    def client(self) -> Any:
        """Return the RosClient (created on first use)."""
        if self._client is None:
            if self.client_factory is None:
                raise RuntimeError("this door has no ROS client")
            self._client = self.client_factory()
        return self._client


class SimTimeUnavailable(RuntimeError):
    """`--use-sim-time` asked of a door whose shared node runs on wall time."""

    cli_message = (
        "--use-sim-time needs a node of this command's own: run the command in a terminal "
        "(a JupyterLab terminal, or `!ros2 ...` in a cell); the cells' `%ros2` commands "
        "share one node on wall time."
    )


def settled_client(args: argparse.Namespace, ctx: Context) -> Any:
    """Return the client once it has discovered the whole graph (`--spin-time` at least)."""
    client = ctx.client
    if getattr(args, "use_sim_time", False) and not client.uses_sim_time:
        raise SimTimeUnavailable()
    client.settle(min_age_s=requested_spin_time(args))
    return client
