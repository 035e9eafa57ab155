"""The tutorial's own launch file from rosject/ (lesson 10), in the session's workspace."""

from __future__ import annotations

import pytest

from course_lib.core.paths import WORKSPACE_INSTALL_DIR
from course_lib.launch import launch
from course_lib.session.session import Session

pytestmark = [pytest.mark.ros, pytest.mark.slow]


@pytest.mark.skipif(
    not (WORKSPACE_INSTALL_DIR / "share" / "parameter_tests").is_dir(),
    reason="rosject/ is not built (python -m course_lib build)",
)
def test_tutorial_launch_sets_velocity(launch_session: Session, tmp_path) -> None:
    handle = launch(
        "parameter_tests",
        "test_parameters.launch.py",
        session=launch_session,
        env={"ROS_LOG_DIR": str(tmp_path)},
    )
    try:
        line = handle.wait_for(r"Velocity parameter is|process has died", 20.0)
        assert line is not None and "0.200000" in line, handle.text
    finally:
        code = handle.stop()
    assert code == 0
    assert handle.output[2].startswith("[INFO] [param_vel-1]: process started with pid [")
    assert handle.output[-1].startswith("[INFO] [param_vel-1]: process has finished cleanly")
