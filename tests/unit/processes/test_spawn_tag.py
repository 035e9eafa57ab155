"""The spawn tag tells a process the course started from one that inherited its tags (a
learner's program started from a lab terminal): what `make stop` and the reaper go by."""

from __future__ import annotations

from course_lib.processes.orphans import command_tag, descended_from, runs_as_spawned


def test_the_spawn_tag_matches_the_command_as_proc_shows_it() -> None:
    tag = command_tag(["jupyter", "lab", "--no-browser"])
    # run through a `#!` interpreter, from PATH: the interpreter comes first, the path in full
    assert runs_as_spawned(["/venv/bin/python3", "/venv/bin/jupyter", "lab", "--no-browser"], tag)
    assert not runs_as_spawned(["/bin/bash", "--rcfile", "lab_bashrc.bash", "-i"], tag)
    assert not runs_as_spawned(["sleep", "600"], tag)
    assert not runs_as_spawned(["/venv/bin/jupyter", "lab"], tag)


def test_a_killed_labs_leftovers_are_those_its_owner_tags_lead_back_to() -> None:
    # lab 100 started the kernel 200, which started the node 300; 400 is another owner's
    reaped = {200: 100, 300: 200, 500: 400, 600: 500}
    assert descended_from({100}, reaped) == [200, 300]
    assert descended_from({100}, {500: 400}) == []
    assert descended_from({100, 400}, reaped) == [200, 300, 500, 600]
