"""What the domain wall costs: a real class hub started with and without it (needs root).

Run: sudo .venv/bin/python -m bench.hub_wall [--learners N] [--environment DIR]
Prints, for each of the two hubs: the hub's start-up (`python -m course_lib hub` to "The
class hub is up", the learners' environment already built), the wall's own check at start,
each learner's server start (sign-in to their server answering through the hub, learners one
after another) and each learner's memory once the server is up and idle (RSS and PSS summed
over their processes; the namespaces' own kernel memory is not in either). Creates test
accounts r2pb-<n> and r2pb-admin and removes them after. Skips (exit 0) when not root.
"""

from __future__ import annotations

import argparse
import contextlib
import hashlib
import os
import pwd
import re
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import psutil
import requests

from course_lib.core.paths import REPO_ROOT
from course_lib.hub.guard.wall import wall_problem
from course_lib.hub.launcher import NO_WALL_ENV

_UP = "The class hub is up"
ADMIN = "r2pb-admin"


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def _default_environment() -> Path:
    """The learners' environment the tests build (tests/browser/class_hub.py), if any."""
    digest = hashlib.sha1(str(REPO_ROOT).encode()).hexdigest()[:10]
    return Path(tempfile.gettempdir()) / f"ros2-course-hub-env-{digest}"


def _pids_of(name: str) -> list[psutil.Process]:
    uid = pwd.getpwnam(name).pw_uid
    return [p for p in psutil.process_iter(["uids"]) if p.info["uids"].real == uid]


def _memory_mib(name: str) -> tuple[float, float]:
    rss = pss = 0
    for process in _pids_of(name):
        with contextlib.suppress(psutil.Error):
            full = process.memory_full_info()
            rss, pss = rss + full.rss, pss + full.pss
    return rss / 2**20, pss / 2**20


def _remove(name: str) -> None:
    with contextlib.suppress(KeyError):
        for process in _pids_of(name):
            with contextlib.suppress(psutil.Error):
                process.kill()
        subprocess.run(["userdel", "--remove", name], check=False, capture_output=True)


def _sign_in(url: str, name: str, password: str, timeout: float = 240.0) -> float:
    """Sign in; return the seconds until the learner's server answers through the hub."""
    session = requests.Session()
    page = session.get(f"{url}/hub/login", timeout=30)
    xsrf = re.search(r'name="_xsrf"\s+value="([^"]+)"', page.text)
    form = {"username": name, "password": password, **({"_xsrf": xsrf[1]} if xsrf else {})}
    started = time.monotonic()
    session.post(f"{url}/hub/login", data=form, timeout=60)
    while time.monotonic() - started < timeout:
        reply = session.get(f"{url}/user/{name}/lab", timeout=60)
        if reply.status_code == 200 and f"/user/{name}/lab" in reply.url:
            return time.monotonic() - started
        time.sleep(0.2)
    raise RuntimeError(f"{name}'s server did not answer within {timeout:.0f} s")


def _one_hub(learners: list[str], environment: Path, folder: Path, wall: bool) -> dict:
    port = _free_port()
    config = folder / f"hub-{'wall' if wall else 'nowall'}.yaml"
    config.write_text(
        f"learners: [{', '.join(learners)}]\nadmins: [{ADMIN}]\nport: {port}\n"
        f"environment: {environment}\nstate: {folder / ('state-' + str(wall))}\nidle_minutes: 0\n",
        encoding="utf-8",
    )
    env = {k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "COURSE_"))}
    if not wall:
        env[NO_WALL_ENV] = "1"
    argv = [sys.executable, "-m", "course_lib", "hub", "--config", str(config)]
    started = time.monotonic()
    hub = subprocess.Popen(
        argv, cwd=REPO_ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
    )
    assert hub.stdout is not None
    log = []
    try:
        for line in hub.stdout:
            log.append(line)
            if _UP in line:
                break
        else:
            raise RuntimeError("the hub did not start:\n" + "".join(log[-40:]))
        up = time.monotonic() - started
        walled = any("The domain wall is on" in line for line in log)
        passwords = dict(
            line.split(" ", 1)
            for line in (folder / f"state-{wall}" / "passwords.txt").read_text().splitlines()
        )
        starts, memory = [], []
        for name in learners:
            starts.append(_sign_in(f"http://127.0.0.1:{port}", name, passwords[name].strip()))
            time.sleep(3.0)  # the lab settles: its daemon and machine service are up
            memory.append(_memory_mib(name))
        return {"up": up, "walled": walled, "starts": starts, "memory": memory}
    finally:
        hub.send_signal(signal.SIGINT)
        try:
            hub.wait(120)
        except subprocess.TimeoutExpired:
            hub.kill()
            hub.wait()


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--learners", type=int, default=2)
    parser.add_argument("--environment", type=Path, default=_default_environment())
    args = parser.parse_args()
    if os.geteuid() != 0:
        print("hub_wall: skipped (a class hub needs root and creates accounts)")
        return 0
    t0 = time.perf_counter()
    problem = wall_problem()
    print(f"wall check at the hub's start: {(time.perf_counter() - t0) * 1000:.1f} ms "
          f"({'available' if problem is None else problem})")  # fmt: skip
    learners = [f"r2pb-{i}" for i in range(1, args.learners + 1)]
    with tempfile.TemporaryDirectory(prefix="bench-hub-wall-") as tmp:
        Path(tmp).chmod(0o711)  # the progress service's own account enters its state folder
        try:
            for wall in (False, True):
                for name in (*learners, ADMIN):  # each hub creates its accounts afresh
                    _remove(name)
                result = _one_hub(learners, args.environment, Path(tmp), wall)
                label = "with the wall   " if result["walled"] else "without the wall"
                starts = result["starts"]
                rss = statistics.mean(m[0] for m in result["memory"])
                pss = statistics.mean(m[1] for m in result["memory"])
                print(
                    f"{label}: hub up in {result['up']:.1f} s; server start per learner "
                    f"{', '.join(f'{s:.1f}' for s in starts)} s (median "
                    f"{statistics.median(starts):.1f} s); idle learner {rss:.0f} MiB RSS, "
                    f"{pss:.0f} MiB PSS",
                    flush=True,
                )
        finally:
            for name in (*learners, ADMIN):
                _remove(name)
    return 0


if __name__ == "__main__":
    sys.exit(main())
