"""The course's image (Dockerfile), built with `make image` and run as a learner runs it.

The engine is the one `make image` picks: docker where its engine answers, else podman.
Every container started here carries LABEL, so that one an interrupted run left behind is
removed before the next starts.
"""

from __future__ import annotations

import hashlib
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path

from course_lib.core.host.ports import free_port
from course_lib.core.paths import REPO_ROOT

__all__ = [
    "BUILD_LOG",
    "LABEL",
    "LEARNER_HOME",
    "TEST_IMAGE",
    "Container",
    "engine",
    "host_mounts_of",
    "remove_leftovers",
    "repo2docker",
    "start_build",
]

TEST_IMAGE = "ros2-params-course:test"
LABEL = "ros2-params-course-test=1"
LEARNER_HOME = "/home/jovyan"
BUILD_LOG = REPO_ROOT / "test-artifacts" / "image-build.log"
# Binder's builder. 2024.7.0 is the last release that builds through the engine's Docker API
# (podman's `podman system service` serves it); 2025.8.0 and newer run `podman buildx version`
# first, which Debian 12's podman 4.3 does not have ("unrecognized command").
REPO2DOCKER = "jupyter-repo2docker==2024.7.0"
_URL = re.compile(r"http://127\.0\.0\.1:8888(/lab/tree/\S+)\?token=([0-9a-f]+)")
_OPENER = urllib.request.build_opener(urllib.request.ProxyHandler({}))


def engine() -> str | None:
    """Return the container engine `make image` uses here (None: neither is usable)."""
    docker = shutil.which("docker")
    if docker and subprocess.run([docker, "info"], capture_output=True).returncode == 0:
        return docker
    return shutil.which("podman")


def start_build(
    tag: str = TEST_IMAGE, target: str = "course", *, no_cache: bool = False
) -> subprocess.Popen[bytes]:
    """Start `make image` for `tag` (stage `target`; every layer again with `no_cache`), its
    output in BUILD_LOG; return the running build."""
    BUILD_LOG.parent.mkdir(parents=True, exist_ok=True)
    log = BUILD_LOG.open("wb")
    env = {**os.environ, "IMAGE": tag, "TARGET": target, "NO_CACHE": "1" if no_cache else ""}
    started = subprocess.Popen(
        # niced: beside the suite's timed tests the build only has to end, not to be first
        ["nice", "-n", "10", "make", "--no-print-directory", "image"],
        cwd=REPO_ROOT,
        env=env,
        stdout=log,
        stderr=subprocess.STDOUT,
        start_new_session=True,  # its own group: stopped with the test run's end (killpg)
    )
    log.close()
    return started


def repo2docker() -> Path:
    """Return the `jupyter-repo2docker` program of REPO2DOCKER, installed on first use in a
    virtual environment of its own (kept in the temporary folder for the next run)."""
    digest = hashlib.sha256(REPO2DOCKER.encode()).hexdigest()[:12]
    folder = Path(tempfile.gettempdir()) / f"ros2-course-repo2docker-{digest}"
    program = folder / "bin" / "jupyter-repo2docker"
    if not program.exists():
        shutil.rmtree(folder, ignore_errors=True)
        subprocess.run([sys.executable, "-m", "venv", str(folder)], check=True)
        pip = [str(folder / "bin" / "python"), "-m", "pip", "install", "--quiet"]
        subprocess.run([*pip, "--disable-pip-version-check", REPO2DOCKER], check=True)
    return program


def remove_leftovers(tool: str) -> None:
    """Remove the containers an interrupted run left behind (they carry LABEL)."""
    listed = subprocess.run(
        [tool, "ps", "-aq", "--filter", f"label={LABEL}"], capture_output=True, text=True
    ).stdout.split()
    if listed:
        subprocess.run([tool, "rm", "-f", "-t", "0", *listed], capture_output=True)


@dataclass
class Container:
    """One learner's container of the image: `docker run -p PORT:8888 -v VOLUME:home IMAGE`."""

    tool: str
    image: str
    volume: str
    name: str
    port: int = field(default_factory=free_port)
    started: float = 0.0

    def run(self) -> None:
        """Start it as the README says a learner does (with a test label and a host port)."""
        self.started = time.monotonic()
        subprocess.run(
            [
                self.tool, "run", "-d", "--name", self.name, "--label", LABEL,
                "-p", f"127.0.0.1:{self.port}:8888", "-v", f"{self.volume}:{LEARNER_HOME}",
                self.image,
            ],
            check=True, capture_output=True, text=True,
        )  # fmt: skip

    def logs(self) -> str:
        """Return what the container printed so far."""
        done = subprocess.run([self.tool, "logs", self.name], capture_output=True, text=True)
        return done.stdout + done.stderr

    def lesson_one(self, timeout: float = 60.0) -> tuple[str, str, float]:
        """Wait until lesson 1's address is printed and answers on the host; return its URL
        (with the token), the token, and the seconds from `run` until it answered."""
        deadline = time.monotonic() + timeout
        while True:
            found = _URL.search(self.logs())
            if found:
                url = f"http://127.0.0.1:{self.port}{found[1]}?token={found[2]}"
                try:
                    with _OPENER.open(url, timeout=5) as reply:
                        if reply.status == 200:
                            return url, found[2], time.monotonic() - self.started
                except OSError:
                    pass
            if time.monotonic() > deadline:
                raise AssertionError(f"lesson 1 was never served:\n{self.logs()[-3000:]}")
            time.sleep(0.2)

    @property
    def base_url(self) -> str:
        """Return the lab's address on the host."""
        return f"http://127.0.0.1:{self.port}"

    def exec(self, *command: str, env: dict[str, str] | None = None, workdir: str = "",
             timeout: float = 300.0) -> subprocess.CompletedProcess[str]:  # fmt: skip
        """Run `command` in the container as the learner; return what it did."""
        options = [f"--env={key}={value}" for key, value in (env or {}).items()]
        if workdir:
            options.append(f"--workdir={workdir}")
        return subprocess.run(
            [self.tool, "exec", *options, self.name, *command],
            capture_output=True, text=True, timeout=timeout,
        )  # fmt: skip

    def processes(self) -> list[tuple[int, str, str]]:
        """Return (host PID, user, command) of every process in the container."""
        shown = subprocess.run(
            [self.tool, "top", self.name, "hpid", "user", "args"],
            capture_output=True, text=True, check=True,
        ).stdout.splitlines()[1:]  # fmt: skip
        rows = []
        for line in shown:
            pid, user, args = line.split(None, 2)
            rows.append((int(pid), user, args))
        return rows

    def stop(self, timeout: int = 20) -> float:
        """Stop it as `docker stop` does (SIGTERM, then SIGKILL after `timeout`); return the
        seconds it took."""
        began = time.monotonic()
        subprocess.run(
            [self.tool, "stop", "-t", str(timeout), self.name], capture_output=True, check=True
        )
        return time.monotonic() - began

    def container_id(self) -> str:
        """Return the engine's full id of the container."""
        shown = subprocess.run(
            [self.tool, "inspect", "--format", "{{.Id}}", self.name],
            capture_output=True, text=True, check=True,
        )  # fmt: skip
        return shown.stdout.strip()

    def remove(self) -> None:
        """Remove it (stopped or not); the volume stays."""
        subprocess.run([self.tool, "rm", "-f", "-t", "0", self.name], capture_output=True)


def host_mounts_of(container_id: str) -> list[str]:
    """Return the host's mount points that belong to container `container_id` (its root
    file system, its /dev/shm)."""
    mounts = Path("/proc/self/mountinfo").read_text().splitlines()
    return [line.split()[4] for line in mounts if container_id in line]
