"""The environment's python3 kernel is the course's: ipykernel without debugpy (8 MiB each)."""

from __future__ import annotations

import json

from jupyter_client.kernelspec import KernelSpecManager
from jupyter_kernels import Kernel

from course_lib.core.procfs import cmdline
from course_lib.tools.kernelspec import KERNEL_NAME, LAUNCHER


def test_the_python3_kernel_spec_starts_the_course_launcher_without_a_debugger() -> None:
    spec = KernelSpecManager().get_kernel_spec(KERNEL_NAME)
    assert spec.argv[:3] == ["python", "-m", LAUNCHER], spec.argv
    assert spec.metadata.get("debugger") is False  # JupyterLab shows no debugger panel


def test_a_kernel_runs_cells_without_debugpy_and_says_it_has_no_debugger() -> None:
    kernel = Kernel()
    try:
        _check_kernel(kernel)
    finally:
        kernel.shutdown()


def _check_kernel(kernel: Kernel) -> None:
    assert LAUNCHER in " ".join(cmdline(kernel.pid) or ())
    reply = kernel.client.kernel_info(reply=True, timeout=30)["content"]
    assert "debugger" not in reply.get("supported_features", []), reply
    out = kernel.ok(
        "import json, os, sys\n"
        "print(json.dumps(['debugpy' in sys.modules and sys.modules['debugpy'] is not None,"
        " os.getcwd() in sys.path or '' in sys.path, get_ipython().__class__.__name__]))"
    )
    assert json.loads(out.text) == [False, True, "ZMQInteractiveShell"]
