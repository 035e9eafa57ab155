"""`%ros2` and `%%ros2` in a real IPython kernel: terminal-like HTML, exact plain text."""

from __future__ import annotations

import os
import textwrap
from pathlib import Path

import pytest

pytestmark = [pytest.mark.ros, pytest.mark.slow]

NODE = Path(__file__).resolve().parents[2] / "golden" / "ros2" / "nodes" / "param_vel_node.py"
REPO = Path(__file__).resolve().parents[3]


def _execute(kc, code: str) -> list[dict]:  # type: ignore[no-untyped-def]
    """Run code in the kernel; return its display/stream/error messages."""
    msg_id = kc.execute(code)
    outputs = []
    while True:
        msg = kc.get_iopub_msg(timeout=60)
        if msg["parent_header"].get("msg_id") != msg_id:
            continue
        kind = msg["msg_type"]
        if kind == "status" and msg["content"]["execution_state"] == "idle":
            return outputs
        if kind in ("display_data", "execute_result", "stream", "error"):
            outputs.append({"type": kind, **msg["content"]})


@pytest.fixture(scope="module")
def kernel():  # type: ignore[no-untyped-def]
    from jupyter_client.manager import start_new_kernel

    env = {**os.environ, "PYTHONPATH": str(REPO)}
    km, kc = start_new_kernel(kernel_name="python3", env=env, cwd=str(REPO))
    try:
        setup = textwrap.dedent(f"""
            %load_ext course_lib.notebook.magics
            import sys
            from course_lib import get_session
            from course_lib.ros2 import client
            _child = get_session().spawn([sys.executable, {str(NODE)!r}], name="vel")
            assert client().wait_for_node("/param_vel_node", include_hidden=False, timeout=10)
            assert client().services_ready("/param_vel_node", timeout=10)
        """)
        assert not [o for o in _execute(kc, setup) if o["type"] == "error"]
        yield kc
    finally:
        kc.stop_channels()
        km.shutdown_kernel(now=False)


def test_line_magic_shows_prompt_and_exact_text(kernel) -> None:  # type: ignore[no-untyped-def]
    (out,) = _execute(kernel, "%ros2 param get /param_vel_node velocity")
    assert out["data"]["text/plain"] == "Double value is: 0.0\n"
    assert "$ </span><b>ros2 param get /param_vel_node velocity</b>" in out["data"]["text/html"]


def test_stderr_and_exit_code_are_shown_apart(kernel) -> None:  # type: ignore[no-untyped-def]
    (out,) = _execute(kernel, "%ros2 param get /param_vel_node no_such")
    assert out["data"]["text/plain"] == (
        "Parameter not set\n"  # Jazzy's words, then the course's hint on its own line
        "Hint: there is no parameter 'no_such' and none with a close name; "
        "`%ros2 param list /param_vel_node` lists them.\n"
    )
    assert "color:#c62828" in out["data"]["text/html"]
    assert "[exit code 1]" in out["data"]["text/html"]


def test_cell_magic_runs_each_line(kernel) -> None:  # type: ignore[no-untyped-def]
    cell = (
        "%%ros2\nparam set /param_vel_node velocity 0.2\n# a comment\nros2 param get "
        "/param_vel_node velocity\nparam set /param_vel_node velocity 0.0\n"
    )
    outs = _execute(kernel, cell)
    assert [o["data"]["text/plain"] for o in outs] == [
        "Set parameter successful\n",
        "Double value is: 0.2\n",
        "Set parameter successful\n",
    ]
