"""The skill exercises' verdicts and hints (pure): right answers pass, each mistake gets its
own hint, a hint grows more specific with each attempt, and counts persist in a file."""

from __future__ import annotations

from pathlib import Path

import pytest

from course_lib.config.loader import parse_settings
from course_lib.core.errors import ConfigError
from course_lib.lessons.settings import CourseSettings
from course_lib.lessons.skills.attempts import AttemptLog
from course_lib.lessons.skills.file_values import params_file_of, params_file_value
from course_lib.lessons.skills.judge import (
    HINTS,
    DriveAttempt,
    StartupAttempt,
    StartupTask,
    hint_for,
    judge_drive,
    judge_startup,
)

NODE = "/param_vel_node"
DRIVE = {"distance_m": 0.45, "time_s": 3.0, "tolerance_m": 0.03, "node": NODE}
FILE_TASK = StartupTask(NODE, "param_vel", "velocity", "m/s", 0.12, 0.01, "HOW", True)
LAUNCH_TASK = StartupTask(NODE, "param_vel", "velocity", "m/s", 0.18, 0.01, "HOW", False)


def _drive(attempt: DriveAttempt, number: int = 1):  # type: ignore[no-untyped-def]
    return judge_drive(attempt, number=number, show_hints=True, **DRIVE)


def _start(attempt: StartupAttempt, task: StartupTask = FILE_TASK, number: int = 1):  # type: ignore[no-untyped-def]
    return judge_startup(attempt, task, number=number, show_hints=True)


def test_drive_right_answer_passes() -> None:
    verdict = _drive(DriveAttempt(0.46, 0.15))
    assert verdict.passed and "passed" in verdict.message and not verdict.hint


@pytest.mark.parametrize(
    ("attempt", "kind"),
    [
        (DriveAttempt(0.0, 0.0), "no_motion"),  # an integer refused: velocity stayed 0.0
        (DriveAttempt(0.0, 0.0, "/param_vel_copy", 0.15), "wrong_node"),
        (DriveAttempt(0.30, 0.1), "too_short"),
        (DriveAttempt(0.60, 0.2), "too_far"),
    ],
)
def test_drive_mistakes_get_their_hint(attempt: DriveAttempt, kind: str) -> None:
    verdict = _drive(attempt)
    assert not verdict.passed and verdict.kind == kind
    other = {"elsewhere": attempt.elsewhere, "elsewhere_value": attempt.elsewhere_value}
    assert verdict.hint == hint_for(kind, 1, {**DRIVE, **other})


def test_wrong_node_hint_names_the_node_from_the_second_attempt() -> None:
    attempt = DriveAttempt(0.0, 0.0, "/param_vel_copy", 0.15)
    first, second = _drive(attempt, 1), _drive(attempt, 2)
    assert "/param_vel_copy" not in first.hint
    assert "/param_vel_copy holds velocity 0.15" in second.hint


def test_integer_hint_comes_at_the_second_attempt_of_a_robot_that_did_not_move() -> None:
    hints = [_drive(DriveAttempt(0.0, 0.0), n).hint for n in (1, 2, 3)]
    assert "double" not in hints[0] and "double" in hints[1] and "0.45 ÷ 3" in hints[2]


@pytest.mark.parametrize("kind", sorted(HINTS))
def test_hints_get_more_specific_and_never_start_with_the_answer(kind: str) -> None:
    words = {
        **DRIVE,
        "target": 0.12,
        "how": "THE COMMAND",
        "first": 0.0,
        "measured_m": 0.3,
        "measured_mps": 0.1,
        "elsewhere": "/other",
        "elsewhere_value": 0.16,
    }
    ladder = [hint_for(kind, n, words) for n in (1, 2, 3, 4)]
    assert len(set(ladder[:3])) == 3, ladder  # a new hint each attempt
    assert ladder[3] == ladder[2]  # then the most specific one stays
    assert "THE COMMAND" not in ladder[0]  # the way to start the node is never the first hint
    assert not [h for h in ladder if "0.15" in h]  # lesson 7's answer, 0.45 m ÷ 3 s, never given


def test_startup_right_answer_passes() -> None:
    attempt = StartupAttempt(True, "my_files/fast.yaml", first=0.12, start=0.121, now=0.12,
                             measured_text="the robot drove at 0.12 m/s")  # fmt: skip
    verdict = _start(attempt)
    assert verdict.passed, verdict


@pytest.mark.parametrize(
    ("attempt", "task", "kind"),
    [
        (StartupAttempt(False), FILE_TASK, "not_started"),
        (StartupAttempt(True, "f.yaml", "integer", "1"), FILE_TASK, "integer"),
        (StartupAttempt(True, "", first=0.0, start=0.0, now=0.12), FILE_TASK, "no_file"),
        (StartupAttempt(True, "f.yaml", "wrong_key", key="/param_vel"), FILE_TASK, "wrong_key"),
        # the node ended at start-up: rcl could not open, or could not parse, its file
        (StartupAttempt(True, "f.yaml", "missing_file"), FILE_TASK, "missing_file"),
        (StartupAttempt(True, "f.yaml", "unreadable"), FILE_TASK, "unreadable"),
        # the file said 0.0, the value came with `param set` after the start
        (StartupAttempt(True, "f.yaml", first=0.0, start=0.0, now=0.12), FILE_TASK,
         "after_window"),
        (StartupAttempt(True, "f.yaml", first=0.3, start=0.26, now=0.26), FILE_TASK,
         "wrong_value"),
        (StartupAttempt(True, "l.py", "no_parameter", first=0.0), LAUNCH_TASK, "no_parameter"),
        (StartupAttempt(True, "l.py", "integer", "1"), LAUNCH_TASK, "integer"),
        (StartupAttempt(True, "l.py", first=0.0, elsewhere="/other", elsewhere_value=0.18),
         LAUNCH_TASK, "wrong_node"),
    ],
)  # fmt: skip
def test_startup_mistakes_get_their_hint(
    attempt: StartupAttempt, task: StartupTask, kind: str
) -> None:
    verdict = _start(attempt, task)
    assert not verdict.passed and verdict.kind == kind, verdict
    assert verdict.hint and verdict.message.startswith("Attempt 1: not yet.")


def test_hints_off_in_the_settings_means_no_hint() -> None:
    verdict = judge_startup(StartupAttempt(False), FILE_TASK, number=1, show_hints=False)
    assert not verdict.passed and verdict.hint == ""


def test_attempt_counts_persist_in_the_learners_folder(tmp_path: Path) -> None:
    log = AttemptLog(tmp_path)
    assert log.tally("07 drive").attempts == 0
    log.add("07 drive", False)
    log.add("07 drive", True)
    again = AttemptLog(tmp_path)  # a restarted kernel reads the same file
    assert again.tally("07 drive").attempts == 2 and again.tally("07 drive").passed
    assert again.tally("09 params file").attempts == 0
    (tmp_path / ".exercise_attempts.json").write_text("{broken", encoding="utf-8")
    assert AttemptLog(tmp_path).tally("07 drive").attempts == 0  # counting starts again


def test_the_params_file_is_read_as_rcl_reads_it(tmp_path: Path) -> None:
    path = tmp_path / "p.yaml"
    path.write_text("/param_vel_node:\n  ros__parameters:\n    velocity: 0.12\n")
    assert params_file_value(path, NODE).value == 0.12
    path.write_text("/param_vel:\n  ros__parameters:\n    velocity: 0.12\n")
    found = params_file_value(path, NODE)
    assert found.problem == "wrong_key" and found.key == "/param_vel"
    path.write_text("/**:\n  ros__parameters:\n    velocity: 1\n")
    found = params_file_value(path, NODE)
    assert found.problem == "integer" and found.written == "1"
    path.write_text("/param_vel_node:\n  ros__parameters:\n    velocity: [0.3\n")
    assert params_file_value(path, NODE).problem == "unreadable"  # rcl fails at line 3 too
    assert params_file_value(tmp_path / "nope.yaml", NODE).problem == "missing_file"
    argv = ["/x/param_vel", "--ros-args", "--params-file", "my_files/p.yaml"]
    assert params_file_of(argv, tmp_path) == tmp_path / "my_files/p.yaml"
    assert params_file_of(["/x/param_vel"], tmp_path) is None


@pytest.mark.parametrize(
    ("text", "line", "key", "words"),
    [
        ("drive_exercise:\n  distance_m: 0.9\n  time_s: 3.0\n", 2, "distance_m", "faster"),
        ("drive_exercise:\n  distance_m: 0.2\n  tolerance_m: 0.1\n", 3, "tolerance_m",
         "quarter"),
        ("startup_exercises:\n  launch_mps: 0.2\n", 2, "launch_mps", "pass unsolved"),
        ("startup_exercises:\n  saved_panel_travel_s: 2.05\n", 2, "saved_panel_travel_s",
         "multiple of 0.1"),
        ("startup_exercises:\n  window_s: slow\n", 2, "window_s", "number"),
    ],
)  # fmt: skip
def test_exercise_settings_errors_name_file_and_line(
    text: str, line: int, key: str, words: str
) -> None:
    with pytest.raises(ConfigError) as err:
        parse_settings(text, CourseSettings, source="config/course.yaml")
    assert (err.value.path, err.value.line) == ("config/course.yaml", line)
    assert err.value.key.endswith(key) and words in str(err.value)


# --- issue 59: each verdict names what the learner wrote, the real cause and one next step ---
FAST = "my_files/start_fast.yaml"


def _file_attempt(tmp_path: Path, text: str) -> StartupAttempt:
    """Read `text` as the learner's params file, as the exercise does; the node logged 0.0."""
    path = tmp_path / "start_fast.yaml"
    path.write_text(text, encoding="utf-8")
    found = params_file_value(path, NODE)
    return StartupAttempt(True, FAST, found.problem, found.written, found.key, first=0.0)


def test_a_misspelt_key_in_a_params_file_is_named_with_its_rename(tmp_path: Path) -> None:
    text = "/param_vel_node:\n  ros__parameters:\n    velocty: 0.12\n"
    verdicts = [_start(_file_attempt(tmp_path, text), number=n) for n in (1, 2, 3)]
    assert verdicts[0].kind == "undeclared"
    assert verdicts[0].message == (
        f"Attempt 1: not yet. {FAST} sets `velocty: 0.12`, which /param_vel_node does not "
        "declare: ROS keeps it silently as an undeclared override, so /param_vel_node started "
        "with velocity 0."
    )
    assert verdicts[0].hint.startswith(f"rename `velocty` to `velocity` in {FAST}: ")
    assert verdicts[2].hint == (
        f"make the line `velocty: 0.12` in {FAST} read `velocity: 0.12`, then start the node "
        "again."
    )
    assert not [v for v in verdicts if "launch" in v.message + v.hint]
    # the same value missing from a launch file (lesson 10) keeps the launch file's words
    launch = _start(StartupAttempt(True, "l.py", "no_parameter", first=0.0), LAUNCH_TASK, 3)
    assert launch.message.endswith("started with velocity 0: the launch file sets none.")
    assert launch.hint == "add `parameters=[{'velocity': 0.18}]` to the Node of l.py."


@pytest.mark.parametrize(
    ("text", "kind", "words"),
    [
        ("/param_vel_node:\n  ros__parameters:\n    use_sim_time: false\n", "file_sets_none",
         f"{FAST} sets no `velocity` under `/param_vel_node: ros__parameters:`"),
        ("/param_vel_node:\n  ros__parameters: {}\n", "file_sets_none", "sets no `velocity`"),
        ("/param_vel_node:\n  ros__parameters:\n    param_vel_node:\n      velocity: 0.12\n",
         "nested", "sets `velocity` one level too deep, as `param_vel_node.velocity`"),
        # what rcl refuses to read (the node ends at start-up; real rcl's words in the hints)
        ("/param_vel_node:\n  velocity: 0.12\n", "no_ros_parameters",
         "did not start: in my_files/start_fast.yaml, `velocity` sits right under "
         "`/param_vel_node:`, with no `ros__parameters:` between them"),
        ("/param_vel_node:\n", "empty_section", "`/param_vel_node:` in my_files/start_fast"),
        ("/param_vel_node:\n  ros__parameters:\n", "empty_section", "`ros__parameters:` in"),
        ("ros__parameters:\n  velocity: 0.12\n", "no_node_key", "begins with `ros__parameters:`"),
        ("/param_vel_node:\n  ros__parameters:\n    velocity:\n", "unreadable", "cannot read"),
    ],
)  # fmt: skip
def test_a_params_file_without_the_value_gets_params_file_words(
    tmp_path: Path, text: str, kind: str, words: str
) -> None:
    attempt = _file_attempt(tmp_path, text)
    verdicts = [_start(attempt, number=n) for n in (1, 2, 3)]
    assert verdicts[0].kind == kind and words in verdicts[0].message, verdicts[0]
    assert not [v for v in verdicts if "launch" in v.message + v.hint], verdicts
    assert len({v.hint for v in verdicts}) == 3


def test_a_velocity_above_top_speed_says_the_robot_tops_out() -> None:
    verdicts = [_drive(DriveAttempt(0.79, 0.45), n) for n in (1, 2, 3)]
    assert verdicts[0].kind == "over_top_speed"
    assert verdicts[0].message == (
        "Attempt 1: not yet. the robot drove 0.79 m in 3 s, not 0.45 m (± 3 cm): "
        "/param_vel_node holds velocity 0.45, but the robot tops out at 0.26 m/s, forwards or "
        "backwards, and drove at that. The answer's velocity is distance ÷ time."
    )
    assert "distance = velocity × time" not in " ".join(v.hint for v in verdicts)
    assert verdicts[2].hint == "velocity = 0.45 ÷ 3 (m/s), set as a double on /param_vel_node."
    assert _drive(DriveAttempt(0.79, -0.45)).kind == "over_top_speed"  # backwards, as fast
    assert _drive(DriveAttempt(0.78, 0.26)).kind == "too_far"  # the top speed itself


def test_the_refused_integer_hint_uses_the_learners_value_and_no_value_past_top_speed() -> None:
    own = _drive(DriveAttempt(0.0, 0.0, refused="1"), 2).hint
    assert own == (
        "did `param set` answer 'Set parameter successful'? `1` is read as an integer and "
        "`velocity` is a double, so ROS refused it ('Wrong parameter type') and "
        "/param_vel_node kept velocity 0; write a speed in m/s with a decimal point, at most "
        "0.26."
    )
    assert "`fast` is read as text" in _drive(DriveAttempt(0.0, 0.0, refused="fast"), 2).hint
    generic = _drive(DriveAttempt(0.0, 0.0), 2).hint
    assert "such as 1" not in generic and "at most 0.26" in generic
    assert "1.0" not in own + generic
