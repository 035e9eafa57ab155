"""The environment's python3 kernel is the course's: ipykernel without debugpy (8 MiB each)."""

from __future__ import annotations

import json

import psutil
from jupyter_client.kernelspec import KernelSpecManager
from jupyter_kernels import Kernel

from course_lib.core.host.procfs import cmdline
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


CHANNELS = ("shell_port", "iopub_port", "stdin_port", "control_port", "hb_port")


def test_a_test_kernel_binds_its_channels_to_unix_sockets() -> None:
    """ci88: a TCP port chosen free was taken by another process before the kernel bound it.

    Unix sockets in a folder of the kernel's own cannot be taken in between.
    """
    kernel = Kernel()
    try:
        info = kernel.manager.get_connection_info()
        expected = {f"{info['ip']}-{info[channel]}" for channel in CHANNELS}
        bound = {
            c.laddr for c in psutil.Process(kernel.pid).net_connections(kind="unix") if c.laddr
        }
        assert expected <= bound, (info, bound)
        assert kernel.ok("print(6 * 7)").text == "42\n"
    finally:
        kernel.shutdown()
