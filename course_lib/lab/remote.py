"""Handles, in a kernel, on processes the lab owns: alive or not, their last lines.

A notebook shutting down never stops them (they are not its children); `stop()` asks the lab
to stop its world, as a learner's `world.stop()` means.
"""

from __future__ import annotations

import time

from ..core.errors import CourseError
from ..processes.children import OutputLine
from ..processes.orphans import owner_tag
from .client import MachineClient

__all__ = ["LabProcess"]


class LabProcess:
    """A process of the lab's machine service, named by its owner tag."""

    def __init__(self, name: str, tag: str, client: MachineClient) -> None:
        self.name = name
        self.tag = tag
        self.pid = int(tag.split(":")[0])
        self._client = client

    def __repr__(self) -> str:
        return f"<LabProcess {self.name} pid={self.pid} {'running' if self.alive else 'ended'}>"

    @property
    def alive(self) -> bool:
        return owner_tag(self.pid) == self.tag

    def _status(self) -> dict:
        try:
            return self._client.request("world.status", timeout=5.0)
        except CourseError:  # the lab itself is gone: nothing more to say of its world
            return {"returncode": None, "tail": []}

    @property
    def returncode(self) -> int | None:
        return None if self.alive else self._status().get("returncode")

    @property
    def lines(self) -> list[OutputLine]:
        now = time.time()
        return [OutputLine("stdout", text, now) for text in self._status().get("tail", [])]

    def stop(self, *, timeout: float = 5.0) -> int | None:
        """Ask the lab to stop its world (simulation and view); return the exit code if known."""
        if self.alive:
            self._client.request("world.stop", timeout=max(timeout, 15.0))
        return self.returncode
