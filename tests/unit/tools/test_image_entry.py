"""The image's entry point routes each door's command (course_lib/tools/image_entry.py)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from course_lib.hub.singleuser import DEFAULT_URL
from course_lib.tools.image_entry import IMAGE_PORT, _server_options, image_lab_argv


def test_a_jupyter_servers_command_is_the_labs_options() -> None:
    binder = ["jupyter", "notebook", "--ip=0.0.0.0", "--port=8888"]
    assert _server_options(binder) == ["--ip=0.0.0.0", "--port=8888"]
    assert _server_options(["/usr/bin/jupyter-lab", "--port=9"]) == ["--port=9"]
    assert _server_options(["jupyter", "kernelspec", "list"]) is None
    assert _server_options(["bash"]) is None


def test_the_learners_lab_listens_on_the_containers_port_lesson_1_first() -> None:
    argv = image_lab_argv(Path("learner") / "ros2-params-course")(["--port=9999"])
    assert argv[1] == "lab" and "--no-browser" in argv
    assert "--ServerApp.ip=0.0.0.0" in argv and f"--ServerApp.port={IMAGE_PORT}" in argv
    assert f"--LabApp.default_url={DEFAULT_URL}" in argv
    assert argv[-1] == "--port=9999", "the command's own options come last and win"


def test_another_command_runs_as_it_is_and_an_unknown_one_says_so() -> None:
    def image(*command: str) -> subprocess.CompletedProcess[str]:
        argv = [sys.executable, "-m", "course_lib", "image", *command]
        return subprocess.run(argv, capture_output=True, text=True, timeout=60)

    ran = image("echo", "a", "--b")
    assert (ran.returncode, ran.stdout) == (0, "a --b\n")
    missing = image("no-such-program")
    assert missing.returncode == 127
    assert "No command 'no-such-program' in the course's image." in missing.stderr
