"""The meshcat scene from the model, and offline replays (deterministic bytes)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from course_lib.sim.view.recorder import plan_frames
from course_lib.sim.world.physics import Simulation
from course_lib.viz.replay import replay_html, write_replay
from course_lib.viz.scene import moving_bodies, scene_commands

pytestmark = pytest.mark.sim

PLAN = [(0.2, 0.0, 1.0), (0.0, 0.8, 1.0)]


def _replay() -> str:
    sim = Simulation()
    return replay_html(sim.model, plan_frames(sim, PLAN))


def test_scene_draws_every_visible_geom_of_the_model() -> None:
    sim = Simulation()
    commands = scene_commands(sim.model, sim.data)
    drawn = {c.path.lower().rsplit("/", 1)[1] for c in commands if type(c).__name__ == "SetObject"}
    expected = {sim.model.geom(i).name for i in range(sim.model.ngeom)}
    assert drawn == expected
    assert {"wheel_left", "lidar_head", "camera_board", "caster_left", "floor"} <= drawn
    assert [sim.model.body(b).name for b in moving_bodies(sim.model)] == [
        "base_link",
        "wheel_left_link",
        "wheel_right_link",
    ]


def test_replay_is_byte_identical_between_runs() -> None:
    assert _replay() == _replay()


def test_replay_is_standalone(tmp_path: Path) -> None:
    sim = Simulation()
    page = write_replay(tmp_path / "run.html", sim.model, plan_frames(sim, PLAN)).read_text()
    assert "MeshCat.Viewer" in page and "http://" not in page.split("<script>")[-1]
    assert page.count("handle_command_bytearray(bytes(") > 20


def test_replay_needs_frames() -> None:
    with pytest.raises(ValueError, match="at least one frame"):
        replay_html(Simulation().model, [])


def test_replay_title_is_escaped() -> None:
    sim = Simulation()
    page = replay_html(sim.model, plan_frames(sim, PLAN[:1]), title="</title><script>x</script>")
    assert "<title>&lt;/title&gt;&lt;script&gt;x&lt;/script&gt;</title>" in page


def _with_plot() -> str:
    from course_lib.viz.speed_svg import speed_svg

    sim = Simulation()
    frames = plan_frames(sim, PLAN)
    samples = [(f.time_s, 0.2) for f in frames]
    return replay_html(sim.model, frames, plot_svg=speed_svg(samples, [(0.5, "velocity := 0.2")]))


def test_replay_with_speed_plot_is_byte_identical_and_loads_nothing() -> None:
    page = _with_plot()
    assert page == _with_plot()
    assert page.count('class="mark"') == 1 and 'id="playhead"' in page
    # the viewer script names the XHTML namespace (a string, never fetched); nothing else
    assert set(re.findall(r"https?://[^\s\"'<>)]+", page)) <= {"http://www.w3.org/1999/xhtml"}
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:|//)""", page)


def test_a_reader_of_the_previous_page_never_sees_half_of_the_new_one(tmp_path: Path) -> None:
    sim = Simulation()
    path = write_replay(tmp_path / "run.html", sim.model, plan_frames(sim, PLAN[:1]))
    before = path.read_bytes()
    with path.open("rb") as reader:  # a browser still reading the page saved before
        write_replay(path, sim.model, plan_frames(sim, PLAN))
        assert reader.read() == before
    assert path.read_bytes() != before
    assert [p.name for p in tmp_path.iterdir()] == ["run.html"]  # no temporary file left
