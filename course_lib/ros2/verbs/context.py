"""What a running `ros2` verb may use: its console, a ROS client made on first use, cwd/env."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from .console import Console

__all__ = ["Context"]


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
