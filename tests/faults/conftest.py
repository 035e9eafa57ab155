"""Fixtures of the fault tests: real kernels, and the check that none leaves a process behind."""

from __future__ import annotations

from collections.abc import Callable, Iterator

import pytest
from jupyter_kernels import Kernel, describe, pid_alive, process_tree, wait_gone


@pytest.fixture
def start_kernel() -> Iterator[Callable[[], Kernel]]:
    """Start kernels on demand; shut them down after the test and check nothing is left."""
    kernels: list[Kernel] = []
    trees: list[int] = []

    def start() -> Kernel:
        kernel = Kernel()
        kernels.append(kernel)
        return kernel

    yield start
    for kernel in kernels:
        if pid_alive(kernel.pid):
            trees += process_tree(kernel.pid)
        kernel.shutdown()
    left = wait_gone(trees, 10.0)
    assert not left, f"processes left behind:\n{describe(left)}"


@pytest.fixture
def lab_kernel(lab) -> Iterator[Callable[[], Kernel]]:  # type: ignore[no-untyped-def]
    """Start kernels with the environment JupyterLab gives the kernels of the module's `lab`."""
    from suite_env import independent_env

    from course_lib.core.paths import runtime_dir
    from course_lib.lab.protocol import SOCKET_ENV

    kernels: list[Kernel] = []
    socket = runtime_dir() / f"lab-{lab.process.pid}.sock"
    env = independent_env(
        ROS_DOMAIN_ID=str(lab.domain_id), COURSE_LAB="1", **{SOCKET_ENV: str(socket)}
    )

    def start() -> Kernel:
        kernel = Kernel(env=env)
        kernels.append(kernel)
        return kernel

    yield start
    for kernel in kernels:
        kernel.shutdown()
