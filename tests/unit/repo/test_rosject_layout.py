"""The ROS packages in rosject/ follow the layouts colcon expects (ament_python, interfaces)."""

from __future__ import annotations

import ast
import configparser
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml

from course_lib.core.paths import ROSJECT_DIR

ALL_PACKAGES = sorted(p.parent for p in ROSJECT_DIR.glob("*/package.xml"))


def _build_type(package: Path) -> str | None:
    return ET.parse(package / "package.xml").getroot().findtext("export/build_type")


PACKAGES = [p for p in ALL_PACKAGES if _build_type(p) == "ament_python"]
INTERFACE_PACKAGES = [p for p in ALL_PACKAGES if _build_type(p) == "ament_cmake"]


def _setup_call(package: Path) -> ast.Call:
    tree = ast.parse((package / "setup.py").read_text())
    calls = [n for n in ast.walk(tree) if isinstance(n, ast.Call)]
    return next(c for c in calls if getattr(c.func, "id", None) == "setup")


def _keyword(call: ast.Call, name: str) -> ast.expr:
    return next(k.value for k in call.keywords if k.arg == name)


def test_workspace_has_the_tutorial_package() -> None:
    assert ROSJECT_DIR / "parameter_tests" in PACKAGES


@pytest.mark.parametrize("package", PACKAGES, ids=lambda p: p.name)
def test_names_agree(package: Path) -> None:
    name = ET.parse(package / "package.xml").getroot().findtext("name")
    assert name == package.name
    assert (package / "resource" / name).is_file(), "resource marker missing"
    assert (package / name / "__init__.py").is_file(), "python package missing"
    setup_py = (package / "setup.py").read_text()
    assert f"package_name = '{name}'" in setup_py


@pytest.mark.parametrize("package", PACKAGES, ids=lambda p: p.name)
def test_manifest_is_format_3_ament_python(package: Path) -> None:
    root = ET.parse(package / "package.xml").getroot()
    assert root.get("format") == "3"
    assert root.findtext("export/build_type") == "ament_python"


@pytest.mark.parametrize("package", PACKAGES, ids=lambda p: p.name)
def test_scripts_go_to_lib_package(package: Path) -> None:
    cfg = configparser.ConfigParser()
    cfg.read(package / "setup.cfg")
    assert cfg["develop"]["script_dir"] == f"$base/lib/{package.name}"
    assert cfg["install"]["install_scripts"] == f"$base/lib/{package.name}"


@pytest.mark.parametrize("package", PACKAGES, ids=lambda p: p.name)
def test_every_launch_and_config_file_is_installed(package: Path) -> None:
    data_files = ast.unparse(_keyword(_setup_call(package), "data_files"))
    for folder, pattern in (("launch", "launch/*.launch.*"), ("config", "config/*.yaml")):
        if any((package / folder).glob("*")):
            assert f"glob('{pattern}')" in data_files, f"{folder}/ is not installed"
            assert all(p.match(pattern.split("/")[1]) for p in (package / folder).iterdir())


@pytest.mark.parametrize(
    "params_file", sorted(ROSJECT_DIR.glob("*/config/*.yaml")), ids=lambda p: p.name
)
def test_params_files_have_ros_parameters_under_a_node_key(params_file: Path) -> None:
    data = yaml.safe_load(params_file.read_text())
    assert isinstance(data, dict) and data
    for node_key, section in data.items():
        assert node_key == "/**" or node_key.startswith("/"), node_key
        assert "ros__parameters" in section, f"{node_key} has no ros__parameters"


def test_tutorial_node_matches_the_tutorial() -> None:
    source = (ROSJECT_DIR / "parameter_tests/parameter_tests/parameter_tests_node.py").read_text()
    assert "super().__init__('param_vel_node')" in source
    assert "Sets the velocity (in m/s) of the robot." in source
    assert "create_timer(0.1" in source
    assert "# self.add_on_set_parameters_callback(" in source
    setup_py = (ROSJECT_DIR / "parameter_tests/setup.py").read_text()
    assert "'param_vel = parameter_tests.parameter_tests_node:main'" in setup_py


def test_every_package_is_python_or_interfaces() -> None:
    assert sorted(PACKAGES + INTERFACE_PACKAGES) == ALL_PACKAGES
    assert ROSJECT_DIR / "tf2_msgs" in INTERFACE_PACKAGES
    assert ROSJECT_DIR / "turtlesim" in INTERFACE_PACKAGES  # its interfaces and rclpy nodes


@pytest.mark.parametrize("package", INTERFACE_PACKAGES, ids=lambda p: p.name)
def test_interface_package_generates_every_message(package: Path) -> None:
    root = ET.parse(package / "package.xml").getroot()
    assert root.get("format") == "3" and root.findtext("name") == package.name
    assert root.findtext("member_of_group") == "rosidl_interface_packages"
    cmake = (package / "CMakeLists.txt").read_text()
    assert f"project({package.name})" in cmake and "rosidl_generate_interfaces(" in cmake
    for folder in ("msg", "srv", "action"):
        for interface in sorted((package / folder).glob(f"*.{folder}")):
            assert f'"{folder}/{interface.name}"' in cmake, f"{interface.name} is not generated"


def test_tf2_msgs_has_jazzys_tf_message() -> None:
    text = (ROSJECT_DIR / "tf2_msgs" / "msg" / "TFMessage.msg").read_text()
    fields = [line for line in text.splitlines() if line.strip() and not line.startswith("#")]
    assert fields == ["geometry_msgs/TransformStamped[] transforms"]
