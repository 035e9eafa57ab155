"""What `make stop` prints: one line per stopped process, and the lab it keeps."""

from __future__ import annotations

from course_lib.processes.stopping import Stopped, StopReport


def test_each_stopped_process_is_one_line_with_its_name_and_pid() -> None:
    report = StopReport(
        stopped=[Stopped("param_vel", 41, "SIGINT"), Stopped("simulation", 42, "SIGKILL")]
    )
    assert report.render() == (
        "Stopped 2 course process(es):\n  param_vel (pid 41)\n  simulation (pid 42) after SIGKILL"
    )


def test_nothing_to_stop_says_so() -> None:
    assert StopReport().render() == "No course process runs."


def test_inside_a_lab_it_says_the_lab_keeps_running() -> None:
    said = StopReport(kept_lab=7).render().splitlines()
    assert said[0] == "No course process runs."
    assert said[1].startswith("This terminal belongs to the lab (pid 7): its JupyterLab and ")
