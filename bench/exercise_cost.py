"""What each skill exercise adds to its lesson's run: arming, the learner's node (re)start, the
check, each with a right answer, in wall seconds (a busy machine shows more).

Run: .venv/bin/python -m bench.exercise_cost
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

from course_lib.config.course import load_course_settings
from course_lib.lessons import Lesson
from course_lib.ros2.api import nodes_and_params as api
from course_lib.session.session import get_session

LAUNCH = """from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([Node(package='parameter_tests', executable='param_vel',
                                   name='param_vel_node', parameters=[{{'velocity': {v}}}])])
"""


def _timed(what: str, action) -> object:  # type: ignore[no-untyped-def]
    start = time.monotonic()
    result = action()
    print(f"  {what}: {time.monotonic() - start:.1f} s")
    return result


def main() -> None:
    from course_lib.lessons.skills import exercises

    session = get_session()
    settings = load_course_settings()
    folder = Path(tempfile.mkdtemp(prefix="exercise-bench-"))
    base = Lesson(7, session, settings)
    base.learner_dir = folder
    base.world(show=False)

    def stop_nodes() -> None:  # the world keeps running, as in a lab
        for child in session.children:
            if child.pid != base.current_world.process.pid:
                child.stop()

    def lesson(number: int) -> Lesson:
        made = Lesson(number, session, settings)
        made.learner_dir, made._world = folder, base._world
        return made

    print("lesson 7, drive a distance in a time:")
    l7 = lesson(7)
    l7.run("parameter_tests", "param_vel")
    drive = exercises.DriveExercise(l7)
    _timed("arm", drive.arm)
    d = settings.drive_exercise
    api.param_set("/param_vel_node", "velocity", round(d.distance_m / d.time_s, 3))
    print("   ", _timed("check", drive.check).message)  # type: ignore[attr-defined]
    stop_nodes()

    print("lesson 9, restart with an edited params file:")
    l9 = lesson(9)
    startup = exercises.ParamsFileExercise(l9)
    _timed("arm", startup.arm)
    path = folder / "fast.yaml"
    v = settings.startup_exercises.params_file_mps
    path.write_text(f"/param_vel_node:\n  ros__parameters:\n    velocity: {v}\n")
    _timed("restart", lambda: l9.run("parameter_tests", "param_vel", "--ros-args",
                                     "--params-file", str(path)))  # fmt: skip
    print("   ", _timed("check", startup.check).message)  # type: ignore[attr-defined]
    stop_nodes()

    print("lesson 10, a launch file of one's own:")
    l10 = lesson(10)
    launch = exercises.LaunchExercise(l10)
    _timed("arm", launch.arm)
    file = folder / "mine.launch.py"
    file.write_text(LAUNCH.format(v=settings.startup_exercises.launch_mps))
    run = _timed("launch", lambda: l10.launch(str(file)))
    print("   ", _timed("check", launch.check).message)  # type: ignore[attr-defined]
    run.stop()  # type: ignore[attr-defined]

    print("lesson 11, a saved value survives a restart:")
    l11 = lesson(11)
    node = ("parameter_descriptors", "descriptor_vel", "--ros-args", "-p", "use_sim_time:=true")
    l11.run(*node)
    saved = exercises.SavedPanelExercise(l11)
    _timed("arm", saved.arm)
    panel_file = folder / "panel.yaml"
    t = settings.startup_exercises.saved_panel_travel_s
    panel_file.write_text(f"/descriptor_vel_node:\n  ros__parameters:\n    travel_time: {t}\n")
    l11.stop("descriptor_vel")
    _timed("restart", lambda: l11.run(*node, "--params-file", str(panel_file)))
    print("   ", _timed("check", saved.check).message)  # type: ignore[attr-defined]
    stop_nodes()
    base.current_world.stop()
    session.close()


if __name__ == "__main__":
    main()
