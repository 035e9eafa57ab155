"""The course's rosdep: one line when every dependency is installed, the missing ones named."""

from __future__ import annotations

from pathlib import Path

import pytest

from course_lib.tools import rosdep

MANIFEST = """<?xml version="1.0"?>
<package format="3"><name>{name}</name>
{deps}<test_depend>ament_copyright</test_depend></package>
"""


def _package(src: Path, name: str, *deps: str) -> None:
    (src / name).mkdir(parents=True)
    lines = "".join(f"<depend>{d}</depend>\n" for d in deps)
    (src / name / "package.xml").write_text(MANIFEST.format(name=name, deps=lines))


def test_all_installed_says_so_in_one_line(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    _package(tmp_path / "src", "mine", "rclpy", "python3-yaml", "other")
    _package(tmp_path / "src", "other", "std_msgs")
    code = rosdep.main(["install", "-i", "--from-path", str(tmp_path / "src"), "-y"])
    out = capsys.readouterr().out
    assert code == 0 and out.splitlines()[0] == rosdep.ALL_THERE


def test_missing_names_what_the_course_offers(
    tmp_path: Path, capsys: pytest.CaptureFixture
) -> None:
    _package(tmp_path / "src", "cpp_thing", "rclcpp", "rclpy")
    code = rosdep.main(["install", "--from-paths", str(tmp_path / "src"), "--rosdistro", "jazzy"])
    err = capsys.readouterr().err
    assert code == 1
    assert "cpp_thing: not in the course's environment: rclcpp (try rclpy" in err


def test_another_distro_is_refused(capsys: pytest.CaptureFixture) -> None:
    assert rosdep.main(["install", "--from-path", "src", "--rosdistro", "humble"]) == 1
    assert "use --rosdistro jazzy" in capsys.readouterr().err
