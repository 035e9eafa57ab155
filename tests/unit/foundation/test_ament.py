"""Package lookup through an ament index, as `ros2 run` and `ros2 pkg` do it."""

from __future__ import annotations

from pathlib import Path

import pytest

from course_lib import ament
from course_lib.errors import ExecutableNotFoundError, PackageNotFoundError


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


def test_workspace_env_overlays_the_course_workspace() -> None:
    env = ament.workspace_env({"PATH": "/usr/bin"})
    assert env["AMENT_PREFIX_PATH"].split(":")[0].endswith("rosject/install")
    assert env["PATH"].endswith(":/usr/bin")
    if ament.list_packages(env):  # built: the package's python path comes from its hooks
        assert any(p.endswith("site-packages") for p in env["PYTHONPATH"].split(":"))
