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
