"""The instructor YAML loader and the simulation settings schema: pure, no MuJoCo."""

from __future__ import annotations

from pathlib import Path

import pytest

from course_lib.config import SimulationSettings, load_simulation_settings, parse_settings
from course_lib.config.simulation import simulation_yaml
from course_lib.core.errors import ConfigError

SOURCE = "config/simulation.yaml"


def _error(text: str) -> ConfigError:
    with pytest.raises(ConfigError) as caught:
        parse_settings(text, SimulationSettings, source=SOURCE)
    return caught.value


def test_the_shipped_file_is_valid() -> None:
    assert isinstance(load_simulation_settings(simulation_yaml()), SimulationSettings)


def test_empty_text_gives_defaults() -> None:
    assert parse_settings("", SimulationSettings) == SimulationSettings()


def test_values_are_read_into_frozen_dataclasses() -> None:
    settings = parse_settings(
        "start_pose:\n  x_m: 1\n  yaw_deg: 90\nrates: {odom_hz: 20}\n", SimulationSettings
    )
    assert settings.start_pose.x_m == 1.0 and isinstance(settings.start_pose.x_m, float)
    assert settings.rates.odom_hz == 20.0
    with pytest.raises(AttributeError):
        settings.rates.odom_hz = 3.0  # type: ignore[misc]


def test_wrong_type_names_file_line_and_key() -> None:
    err = _error("# comment\nrates:\n  clock_hz: 50\n  odom_hz: fast\n")
    assert (err.path, err.line, err.key) == (SOURCE, 4, "rates.odom_hz")
    assert "expected a number, got 'fast'" in str(err)


def test_unknown_key_suggests_the_closest() -> None:
    err = _error("start_pose:\n  x: 1.0\n")
    assert (err.line, err.key) == (2, "start_pose.x")
    assert "did you mean `x_m`?" in err.hint


def test_out_of_range_value_says_the_limit() -> None:
    err = _error("lidar:\n  samples: 2\n")
    assert (err.line, err.key) == (2, "lidar.samples")
    assert "at least 4" in err.hint


def test_boolean_is_not_a_number() -> None:
    assert _error("timestep_s: true\n").key == "timestep_s"


def test_obstacle_checks_point_at_the_field() -> None:
    text = (
        "obstacles:\n  - name: crate\n    shape: box\n    position_m: [1, 0]\n"
        "    size_m: [0.2, 0.2]\n"
    )
    err = _error(text)
    assert (err.line, err.key) == (5, "obstacles[0].size_m")
    assert "[length, width, height]" in err.hint


def test_unknown_shape_lists_the_choices() -> None:
    err = _error("obstacles:\n  - {name: a, shape: cone, position_m: [0, 0], size_m: [1, 1]}\n")
    assert err.key == "obstacles[0].shape" and "'box', 'cylinder'" in err.hint


def test_duplicate_obstacle_names_are_rejected() -> None:
    item = "  - {name: a, shape: cylinder, position_m: [0, 0], size_m: [1, 1]}\n"
    assert "used twice" in str(_error("obstacles:\n" + item + item))


def test_missing_required_key_is_named() -> None:
    err = _error("obstacles:\n  - {name: a, shape: box, size_m: [1, 1, 1]}\n")
    assert err.key == "obstacles[0].position_m"


def test_syntax_error_has_a_line() -> None:
    err = _error("rates:\n  odom_hz: [1,\n")
    assert err.key == "(syntax)" and err.line is not None


def test_file_errors_name_the_file(tmp_path: Path) -> None:
    bad = tmp_path / "simulation.yaml"
    bad.write_text("real_time_factor: -1\n")
    with pytest.raises(ConfigError) as caught:
        load_simulation_settings(bad)
    assert caught.value.path.endswith("simulation.yaml") and caught.value.line == 1
