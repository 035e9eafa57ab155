"""Package lookup through an ament index, as `ros2 run` and `ros2 pkg` do it."""

from __future__ import annotations

from pathlib import Path

import pytest

from course_lib.core import ament
from course_lib.core.errors import ExecutableNotFoundError, PackageNotFoundError


@pytest.fixture
def prefix(tmp_path: Path) -> Path:
    (tmp_path / "share/ament_index/resource_index/packages").mkdir(parents=True)
    (tmp_path / "share/ament_index/resource_index/packages/demo").touch()
    exe = tmp_path / "lib/demo/talker"
    exe.parent.mkdir(parents=True)
    exe.write_text("#!/bin/sh\n")
    exe.chmod(0o755)
    (tmp_path / "lib/demo/README").write_text("not executable")
    return tmp_path


def test_lookup_through_ament_prefix_path(prefix: Path) -> None:
    env = {"AMENT_PREFIX_PATH": str(prefix)}
    assert ament.package_prefix("demo", env) == prefix
    assert ament.package_share_directory("demo", env) == prefix / "share/demo"
    assert ament.package_executables("demo", env) == ["talker"]
    assert ament.find_executable("demo", "talker", env) == prefix / "lib/demo/talker"
    assert ament.list_packages(env) == {"demo": prefix}


def test_missing_package_and_executable_use_ros2_run_wording(prefix: Path) -> None:
    env = {"AMENT_PREFIX_PATH": str(prefix)}
    with pytest.raises(PackageNotFoundError, match=r"^Package 'nope' not found"):
        ament.package_prefix("nope", env)
    with pytest.raises(ExecutableNotFoundError, match=r"^No executable found") as err:
        ament.find_executable("demo", "listener", env)
    assert "talker" in err.value.hint


def _prefix_with(root: Path, package: str) -> Path:
    (root / "share/ament_index/resource_index/packages").mkdir(parents=True)
    (root / "share/ament_index/resource_index/packages" / package).touch()
    return root


def test_first_prefix_in_the_callers_order_wins(tmp_path: Path) -> None:
    mine = _prefix_with(tmp_path / "mine", "demo")
    theirs = _prefix_with(tmp_path / "theirs", "demo")
    for order in ([mine, theirs], [theirs, mine]):
        env = {"AMENT_PREFIX_PATH": ":".join(map(str, order))}
        assert ament.package_prefix("demo", env) == order[0]
        assert ament.list_packages(env) == {"demo": order[0]}


def test_workspace_env_keeps_a_learners_workspace_before_the_course_one(tmp_path: Path) -> None:
    course = str(ament.WORKSPACE_INSTALL_DIR)
    mine = str(tmp_path / "my_ws/install")
    sourced_after = ament.workspace_env({"AMENT_PREFIX_PATH": f"{mine}:{course}"})
    assert sourced_after["AMENT_PREFIX_PATH"] == f"{mine}:{course}"
    sourced_before = ament.workspace_env({"AMENT_PREFIX_PATH": f"{course}:{mine}"})
    assert sourced_before["AMENT_PREFIX_PATH"] == f"{course}:{mine}"
    without_course = ament.workspace_env({"AMENT_PREFIX_PATH": mine})
    assert without_course["AMENT_PREFIX_PATH"] == f"{mine}:{course}"


def test_workspace_env_overlays_the_course_workspace() -> None:
    env = ament.workspace_env({"PATH": "/usr/bin"})
    assert env["AMENT_PREFIX_PATH"].split(":")[0].endswith("rosject/install")
    assert env["PATH"].endswith(":/usr/bin")
    if ament.list_packages(env):  # built: the package's python path comes from its hooks
        assert any(p.endswith("site-packages") for p in env["PYTHONPATH"].split(":"))


def _hooked_prefix(root: Path, hooks: dict[str, str]) -> Path:
    """Return an install prefix whose packages' package.dsv files hold `hooks`."""
    for package, text in hooks.items():
        (root / "share/colcon-core/packages").mkdir(parents=True, exist_ok=True)
        (root / "share/colcon-core/packages" / package).write_text("")
        (root / "share" / package).mkdir(parents=True, exist_ok=True)
        (root / "share" / package / "package.dsv").write_text(text)
    return root


def _overlaid(prefix: Path) -> dict[str, str]:
    env: dict[str, str] = {}
    ament._overlay(env, prefix)
    return env


def test_package_hooks_are_read_again_when_one_changes(tmp_path: Path) -> None:
    """The daemon keeps the hooks' actions between commands: a rebuilt, added or removed
    package must still show in the next command's environment."""
    prefix = _hooked_prefix(tmp_path, {"a": "set;A_VALUE;one\n"})
    assert _overlaid(prefix) == {"A_VALUE": str(prefix / "one")}
    assert _overlaid(prefix) == {"A_VALUE": str(prefix / "one")}  # kept
    (prefix / "share/a/package.dsv").write_text("set;A_VALUE;three\n")  # rebuilt
    assert _overlaid(prefix) == {"A_VALUE": str(prefix / "three")}
    _hooked_prefix(prefix, {"b": "prepend-non-duplicate;B_PATH;lib\n"})
    assert _overlaid(prefix) == {"A_VALUE": str(prefix / "three"), "B_PATH": str(prefix / "lib")}
    (prefix / "share/colcon-core/packages/a").unlink()
    assert _overlaid(prefix) == {"B_PATH": str(prefix / "lib")}
