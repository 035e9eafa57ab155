"""tf2_msgs builds from a clean copy with the course's own build step, and is Jazzy's type."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.core.paths import REPO_ROOT, ROSJECT_DIR
from course_lib.processes.domain import isolation_env, lease_domain

pytestmark = [pytest.mark.ros, pytest.mark.slow]

JAZZY_TF_MESSAGE_HASH = "RIHS01_e369d0f05a23ae52508854b66f6aa0437f3449d652e8cbf22d5abe85d020f087"
PUBLISH_AND_HASH = """
import rclpy
from rclpy.serialization import deserialize_message, serialize_message
from tf2_msgs.msg import TFMessage
from geometry_msgs.msg import TransformStamped

message = TFMessage(transforms=[TransformStamped(child_frame_id='base_footprint')])
assert deserialize_message(serialize_message(message), TFMessage) == message
context = rclpy.Context()
rclpy.init(context=context)
node = rclpy.create_node('tf2_msgs_check', context=context)
node.create_publisher(TFMessage, '/tf', 10)
print(node.get_publishers_info_by_topic('/tf')[0].topic_type_hash)
node.destroy_node()
rclpy.shutdown(context=context)
"""


def _build(workspace: Path) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("AMENT_", "COLCON_"))}
    env.pop("CMAKE_PREFIX_PATH", None)
    return subprocess.run(
        [sys.executable, "-m", "course_lib", "build", "--workspace", str(workspace)],
        cwd=REPO_ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Path, float]]:
    """A workspace holding only a fresh copy of rosject/tf2_msgs, built as `make setup` does."""
    workspace = tmp_path_factory.mktemp("clean_clone") / "rosject"
    shutil.copytree(ROSJECT_DIR / "tf2_msgs", workspace / "tf2_msgs")
    started = time.monotonic()
    done = _build(workspace)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    yield workspace / "install", time.monotonic() - started


def test_tf2_msgs_builds_from_scratch(built: tuple[Path, float]) -> None:
    install, _seconds = built  # the time is bench/workspace_build.py's to report
    assert (install / ".built").is_file()
    marker = install / "share/ament_index/resource_index/packages/tf2_msgs"
    assert marker.is_file()
    assert (install / "share/ament_index/resource_index/rosidl_interfaces/tf2_msgs").is_file()


def test_only_the_c_type_supports_are_built(built: tuple[Path, float]) -> None:
    """rclpy uses the C type supports; the C++ ones were half of every build (make setup, the
    learners' environment), for C++ nodes the course does not have."""
    install, _ = built
    libraries = sorted(p.name for p in (install / "lib").glob("libtf2_msgs__*.so"))
    assert "libtf2_msgs__rosidl_typesupport_fastrtps_c.so" in libraries
    assert not [name for name in libraries if name.endswith("_cpp.so")], libraries


def test_msg_file_is_installed_where_interface_files_live(built: tuple[Path, float]) -> None:
    install, _ = built
    installed = install / "share/tf2_msgs/msg/TFMessage.msg"
    assert installed.read_text() == (ROSJECT_DIR / "tf2_msgs/msg/TFMessage.msg").read_text()


def test_generated_type_hash_is_jazzys(built: tuple[Path, float]) -> None:
    install, _ = built
    description = json.loads((install / "share/tf2_msgs/msg/TFMessage.json").read_text())
    hashes = {h["type_name"]: h["hash_string"] for h in description["type_hashes"]}
    assert hashes["tf2_msgs/msg/TFMessage"] == JAZZY_TF_MESSAGE_HASH


def test_built_message_imports_serializes_and_publishes_with_jazzys_hash(
    built: tuple[Path, float],
) -> None:
    install, _ = built
    site = next(install.glob("lib/python3.*/site-packages"))
    lease = lease_domain()
    try:
        env = {**os.environ, **isolation_env(lease.domain_id)}
        env["PYTHONPATH"] = str(site)
        # As a sourced workspace: ROS's type support loads the message libraries by name.
        env["LD_LIBRARY_PATH"] = os.pathsep.join(
            p for p in (str(install / "lib"), env.get("LD_LIBRARY_PATH", "")) if p
        )
        done = subprocess.run(
            [sys.executable, "-c", PUBLISH_AND_HASH],
            cwd=install,
            env=env,
            capture_output=True,
            text=True,
            timeout=60,
            check=False,
        )
    finally:
        lease.release()
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout.strip() == JAZZY_TF_MESSAGE_HASH


def test_second_build_rebuilds_nothing(built: tuple[Path, float]) -> None:
    install, _ = built
    libraries = sorted((install / "lib").glob("libtf2_msgs__*.so"))
    before = {p: p.stat().st_mtime_ns for p in libraries}
    done = _build(install.parent)
    assert done.returncode == 0, done.stderr[-3000:]
    assert {p: p.stat().st_mtime_ns for p in libraries} == before
