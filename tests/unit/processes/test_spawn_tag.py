"""The spawn tag tells a process the course started from one that inherited its tags (a
learner's program started from a lab terminal): what `make stop` and the reaper go by."""

from __future__ import annotations

from course_lib.processes.orphans import command_tag, runs_as_spawned


def test_the_spawn_tag_matches_the_command_as_proc_shows_it() -> None:
    tag = command_tag(["jupyter", "lab", "--no-browser"])
    # run through a `#!` interpreter, from PATH: the interpreter comes first, the path in full
    assert runs_as_spawned(["/venv/bin/python3", "/venv/bin/jupyter", "lab", "--no-browser"], tag)
    assert not runs_as_spawned(["/bin/bash", "--rcfile", "lab_bashrc.bash", "-i"], tag)
    assert not runs_as_spawned(["sleep", "600"], tag)
    assert not runs_as_spawned(["/venv/bin/jupyter", "lab"], tag)
