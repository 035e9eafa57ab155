"""A class through a real hub: N learners signed in and driving, and what the hub itself costs.

Run (root): .venv/bin/python -m bench.hub_class [--learners 16] [--window 30] [--gets 30]
            [--no-wall] [--environment DIR]
Starts the course's class hub (`python -m course_lib hub`, test accounts r2pb-<n>, removed
after), signs each learner in (their server starts through the hub), starts a kernel on each
server through the hub's proxy and runs lesson 7's cells there, with the live speed plot and
the 3D view watched through the proxy. Then every learner drives at once, as in
bench.class_capacity (the same round, goals and tables), and the hub's own processes (the
hub, its proxy, the progress service) are measured over the same window and printed apart,
with their share per learner. Needs the learners' environment (the hub builds it on its first
start; the class hub tests build it too). Skips (exit 0) when not root.
"""

from __future__ import annotations

import argparse
import inspect
import os
import signal
import sys
import tempfile
import time
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any

import psutil

from bench import _capacity_kernel
from bench._capacity_report import (
    Round,
    hub_summary,
    record_hub,
)
from bench._hub import (
    Hub,
    account_pids,
    default_environment,
    running_hub,
    server_token,
    sign_in,
)
from bench._hub_kernel import HubKernel
from bench._labs import tree_pids
from bench.class_capacity import (
    GETS_PER_S,
    OTHERS_LIMIT,
    SETUP,
    Views,
    drive_round,
    measured_round,
)

# The learner's copy of the course has no bench/: the drive's code goes to the kernel first.
_INSTALL_DRIVE = """\
import sys, types
_bench = sys.modules.setdefault("bench", types.ModuleType("bench"))
_drive = types.ModuleType("bench._capacity_kernel")
exec(compile({source!r}, "bench/_capacity_kernel.py", "exec"), _drive.__dict__)
sys.modules["bench._capacity_kernel"] = _bench._capacity_kernel = _drive
"""


@dataclass
class HubLearner:
    """One signed-in learner: their account, their kernel through the hub, their 3D view."""

    number: int
    name: str
    hub: Hub
    kernel: HubKernel
    viewer_port: int = 0
    view_updates: int = 0

    @property
    def roots(self) -> list[int]:
        return [p.pid for p in account_pids(self.name)]

    def view_request(self) -> Any:
        """Return the 3D view's websocket request, through the hub's proxy."""
        from tornado.httpclient import HTTPRequest

        url = f"ws://127.0.0.1:{self.hub.port}/user/{self.name}/proxy/{self.viewer_port}/"
        return HTTPRequest(url, headers=self.kernel.headers)

    def stop(self) -> None:
        self.kernel.shutdown()


def add_learner(hub: Hub, number: int, views: Views) -> HubLearner:
    """Sign learner `number` in, start a kernel on their server, run lesson 7's first cells."""
    name = f"r2pb-{number}"
    took = sign_in(hub.url, name, hub.passwords[name])
    kernel = HubKernel(f"{hub.url}/user/{name}", server_token(name))
    learner = HubLearner(number, name, hub, kernel)
    try:
        kernel.run(_INSTALL_DRIVE.format(source=inspect.getsource(_capacity_kernel)))
        for cell in SETUP:
            printed = kernel.collect(kernel.submit(cell), timeout=180.0)
        learner.viewer_port = int(printed.split()[-1])
        views.watch(learner)
    except BaseException:
        learner.stop()
        raise
    print(f"  {name}: server up through the hub in {took:.1f} s, lesson 7 running", flush=True)
    return learner


def hub_processes(hub: Hub, learners: list[HubLearner]) -> dict[int, str]:
    """Return the hub's own processes (its tree without the learners'), pid to label."""
    theirs = {pid for learner in learners for pid in tree_pids(learner.roots)}
    labels = {}
    for pid in tree_pids([hub.process.pid]):
        if pid in theirs:
            continue
        try:
            command = " ".join(psutil.Process(pid).cmdline())
        except psutil.NoSuchProcess:
            continue
        labels[pid] = _hub_label(command)
    return labels


def _hub_label(command: str) -> str:
    """Return the name of a hub process from its command line (pure)."""
    for word, label in (
        ("configurable-http-proxy", "proxy (configurable-http-proxy)"),
        ("progress", "progress service"),
        ("idle", "idle culler"),
        ("jupyterhub", "hub (JupyterHub)"),
        ("course_lib hub", "gate (the hub launcher: relays every connection)"),
    ):
        if word in command:
            return label
    return " ".join(Path(a).name for a in command.split()[:3])[:40]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--learners", type=int, default=16)
    parser.add_argument("--window", type=float, default=30.0, help="seconds measured")
    parser.add_argument(
        "--gets", type=int, default=None, help="param gets per learner (one a second)"
    )
    parser.add_argument("--no-wall", action="store_true", help="start the hub without its wall")
    parser.add_argument("--environment", type=Path, default=default_environment())
    parser.add_argument(
        "--record", action="store_true", help="write the hub's figures to deploy/capacity.yaml"
    )
    args = parser.parse_args()
    gets = args.gets or max(1, round(args.window * GETS_PER_S))
    if os.geteuid() != 0:
        print("hub_class: skipped (a class hub needs root and creates accounts)")
        return 0
    signal.signal(signal.SIGTERM, signal.default_int_handler)  # stop everything on SIGTERM too
    print(f"{os.cpu_count()} cores; load average {os.getloadavg()[0]:.2f} before the bench")
    names = [f"r2pb-{i}" for i in range(1, args.learners + 1)]
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="bench-hub-class-") as tmp:
        Path(tmp).chmod(0o711)  # the progress service's own account enters its state folder
        with running_hub(names, args.environment, Path(tmp), wall=not args.no_wall) as hub:
            wall = "with" if hub.walled else "without"
            print(f"hub up in {hub.up_s:.1f} s ({wall} the domain wall)", flush=True)
            views = Views()
            learners: list[HubLearner] = []
            rounds: list[Round] = []
            try:
                for n in sorted({1, args.learners}):  # alone (one pod's needs), then the class
                    while len(learners) < n:
                        learners.append(add_learner(hub, len(learners) + 1, views))
                    own = hub_processes(hub, learners)
                    drive = partial(drive_round, learners, args.window, gets, hub=own)
                    rounds.append(measured_round(drive, OTHERS_LIMIT))
            finally:
                views.stop()
                for learner in reversed(learners):
                    try:
                        learner.stop()
                    except Exception as exc:  # the hub's stop ends it anyway
                        print(f"  {learner.name}'s kernel: {exc}", file=sys.stderr)
    facts = hub_summary(rounds, walled=hub.walled)
    print(
        f"\nThe hub's own cost at N = {facts['learners']}: {facts['own']['cpu_cores']} cores, "
        f"{facts['own']['memory_mib']} MiB ({facts['own']['cpu_cores_per_learner']} cores and "
        f"{facts['own']['memory_mib_per_learner']} MiB per learner); a learner through the hub: "
        f"{facts['learner_memory_mib_alone']} MiB alone, {facts['learner_memory_mib_shared']} "
        f"MiB at N = {facts['learners']}"
    )
    if args.record:
        record_hub(facts)
    print(f"took {time.monotonic() - started:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
