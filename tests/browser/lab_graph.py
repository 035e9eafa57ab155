"""The lab's ROS 2 graph as `ros2` in a lab terminal shows it (tests/browser/terminal.py).

Problems are returned in words (an empty list: all is well), so a walk can go on after one.
"""

from __future__ import annotations

import re
import time
from collections import Counter
from collections.abc import Callable

from terminal import Terminal

__all__ = ["graph_problems", "publishers", "wait_publishers"]


def graph_problems(terminal: Terminal, worlds: int = 1) -> list[str]:
    """Return what is wrong with the lab's ROS 2 graph, as `ros2` in a lab terminal shows it:
    `worlds` /mujoco nodes (one once a lesson started the world), no node name twice, and as
    many publishers of /clock."""
    problems = []
    nodes, code = terminal.run_to_end("ros2 node list")
    names = [line.strip() for line in _plain(nodes).splitlines() if line.strip().startswith("/")]
    twice = sorted(name for name, count in Counter(names).items() if count > 1)
    if code != 0 or names.count("/mujoco") != worlds or twice:
        problems.append(
            f"`ros2 node list` (exit {code}) should list /mujoco {worlds} time(s) and no name "
            f"twice (twice: {twice}):\n{_plain(nodes).strip()}"
        )
    clock, code = terminal.run_to_end("ros2 topic info /clock")
    if worlds and (code != 0 or f"Publisher count: {worlds}\n" not in _plain(clock)):
        problems.append(
            f"`ros2 topic info /clock` (exit {code}) should say Publisher count: {worlds}:\n"
            f"{_plain(clock).strip()}"
        )
    return problems


def _plain(text: str) -> str:
    """Return terminal output without escape sequences and carriage returns."""
    return re.sub(r"\x1b\[[0-9;?]*[A-Za-z]", "", text).replace("\r", "")


def publishers(terminal: Terminal, topic: str) -> tuple[list[str], str]:
    """Return the node names `ros2 topic info <topic> --verbose` lists as publishers, and what
    it printed."""
    info, code = terminal.run_to_end(f"ros2 topic info {topic} --verbose")
    info = _plain(info)
    assert code == 0, info
    names = []
    for block in info.split("\n\n"):
        found = re.search(r"Node name: (\S+)", block)
        if found and "Endpoint type: PUBLISHER" in block:
            names.append(found[1])
    return names, info


def wait_publishers(
    terminal: Terminal, topic: str, done: Callable[[list[str]], object], timeout: float = 30.0
) -> list[str]:
    """Ask `ros2 topic info` again until `done(publishers)` (discovery takes a moment)."""
    deadline = time.monotonic() + timeout
    while True:
        names, info = publishers(terminal, topic)
        if done(names):
            return names
        assert time.monotonic() < deadline, f"{topic}'s publishers never changed:\n{info}"
