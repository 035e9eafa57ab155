"""Helpers of the part-2 golden tests (service, interface, topic info/pub/bw, node info)."""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import threading
import time
from typing import Any

from course_goldens import with_course_interfaces, with_course_services
from ros2_golden import GOLDEN, compare

from course_lib.ros2.command.commands import Context, execute
from course_lib.ros2.verbkit.console import CollectingConsole

CASES = {c["case"]: c for c in json.loads((GOLDEN / "cases_part2.json").read_text())}
WAITING = "waiting for service to become available...\n"
# Cases the course does not copy on purpose, with the reason.
SKIPPED = {
    "service_type_daemon_autostart": "a discovery miss of the real tool (README: the course "
    "finds running nodes); `daemon_service_type` checks the same command",
}
_FIRST_LINE_WAIT_S = 30.0  # at most, for an interrupted command's first line

SUBSCRIBER = (
    "import rclpy, sys\n"
    "from geometry_msgs.msg import Twist\n"
    "rclpy.init()\n"
    "node = rclpy.create_node('cmd_vel_listener')\n"
    "node.create_subscription(Twist, '/cmd_vel', lambda m: None, 10)\n"
    "try:\n"
    "    rclpy.spin(node)\n"
    "except BaseException:\n"
    "    pass\n"
)


def phase(case: dict) -> str:
    """Return which nodes ran: 'empty', 'alone' (tutorial node) or 'four' (all nodes)."""
    notes = " ".join(case["notes"])
    if "nothing else running" in notes:
        return "empty"
    if "tutorial node running alone" in notes:
        return "alone"
    return "four"


def names(which: str, *, streaming: bool = False) -> list[str]:
    """Return the visible `ros2` cases of one phase (streaming: stopped with SIGINT)."""
    return sorted(
        name
        for name, case in CASES.items()
        if case["command"].startswith("ros2 ")
        and phase(case) == which
        and any("stopped with SIGINT" in n for n in case["notes"]) == streaming
    )


def normalize(text: str) -> str:
    """Blank what varies run to run: GIDs, message stamps; drop the optional waiting line."""
    text = re.sub(r"GID: [0-9a-f.]+", "GID: <gid>", text)
    text = re.sub(r"(\n  sec|\n  nanosec): \d+", r"\1: <n>", text)
    return text.replace(WAITING, "").replace(sys.prefix, "<venv>")


def compare2(case: dict, got: tuple[str, str, int]) -> None:
    """Compare with a part-2 case (stdout normalised; `interface package` order is random)."""
    stdout, stderr, code = got
    expected = dict(case, stdout=normalize(case["stdout"]))
    stdout = normalize(stdout)
    if case["command"] == "ros2 interface packages":
        expected["stdout"] = with_course_interfaces(expected["stdout"])
    if case["command"] == "ros2 interface list -s":  # turtlesim's, built in rosject/
        expected["stdout"] = with_course_services(expected["stdout"])
    if case["command"].startswith("ros2 interface package "):
        stdout = "\n".join(sorted(stdout.splitlines()))
        expected["stdout"] = "\n".join(sorted(expected["stdout"].splitlines()))
    compare(expected, (stdout, normalize(stderr), code))


def interrupt_console(env: dict[str, str], command: str, after_s: float) -> tuple[str, str, int]:
    """Run a command line in a terminal's way and press Ctrl-C `after_s` seconds after its
    first line, as a person would once the command has started (every command these tests
    interrupt says something first; on a busy host Python alone can take seconds to start:
    ci63's `topic bw`, interrupted 3.5 s after it was started, had printed no figure yet)."""
    import shlex

    said: dict[str, list[str]] = {"stdout": [], "stderr": []}
    first_line = threading.Event()

    def read(name: str, stream: Any) -> None:
        for line in stream:
            said[name].append(line)
            first_line.set()

    with (
        subprocess.Popen(  # its exit closes the pipes and reaps the process
            [sys.executable, "-m", "course_lib.ros2.command.cli", *shlex.split(command)[1:]],
            env=env,
            cwd=GOLDEN,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            start_new_session=True,
        ) as proc
    ):
        readers = [
            threading.Thread(target=read, args=(name, getattr(proc, name)), daemon=True)
            for name in said
        ]
        for reader in readers:
            reader.start()
        try:
            first_line.wait(_FIRST_LINE_WAIT_S)
            time.sleep(after_s)
            os.killpg(proc.pid, signal.SIGINT)
            proc.wait(timeout=20)
            for reader in readers:
                reader.join(timeout=5)
        finally:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGKILL)
    return "".join(said["stdout"]), "".join(said["stderr"]), proc.returncode


def interrupt_api(command: str, after_s: float) -> tuple[str, str, int]:
    """Run a command line in this process and cancel it after `after_s` (the door's Ctrl-C)."""
    import shlex

    from course_lib.ros2.api import nodes_and_params as api

    console = CollectingConsole()
    timer = threading.Timer(after_s, console.cancelled.set)
    timer.start()
    try:
        code = execute(shlex.split(command)[1:], Context(console, api.client, cwd=str(GOLDEN)))
    finally:
        timer.cancel()
    out = console.result(code)
    return out.stdout, out.stderr, out.exit_code
