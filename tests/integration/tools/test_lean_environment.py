"""What `make setup` keeps out of every process: code generators and grammars built at import."""

from __future__ import annotations

import json
import subprocess
import sys
import sysconfig
from pathlib import Path

from course_lib.tools import rosidl_import
from course_lib.tools.rosidl_import import PTH_NAME, install_pth

GENERATOR_MODULES = ("lark", "em", "rosidl_generator_py.generate_py_impl", "rosidl_parser.parser")


def _run(program: str) -> str:
    done = subprocess.run(
        [sys.executable, "-c", program], capture_output=True, text=True, timeout=60, check=False
    )
    assert done.returncode == 0, done.stderr
    assert done.stderr == ""  # a broken .pth line prints "Error processing line 1 of ..."
    return done.stdout


def test_a_node_of_this_environment_never_loads_the_message_generator() -> None:
    program = f"""
import json, sys
import rclpy
from geometry_msgs.msg import Twist
rclpy.init()
node = rclpy.create_node("no_generator_probe")
node.create_publisher(Twist, "probe_cmd_vel", 1).publish(Twist())
print(json.dumps([m for m in {GENERATOR_MODULES!r} if m in sys.modules]))
node.destroy_node()
rclpy.shutdown()
"""
    assert json.loads(_run(program)) == []


def test_the_generator_is_still_imported_by_a_build_that_asks_for_it() -> None:
    program = """
import rosidl_generator_py
from rosidl_generator_py import generate_py, import_type_support
from rosidl_generator_py.generate_py_impl import generate_py as same
assert generate_py is same and callable(import_type_support)
assert "generate_py" in rosidl_generator_py.__all__
try:
    rosidl_generator_py.no_such_name
except AttributeError as error:
    print(error)
"""
    assert _run(program) == "module 'rosidl_generator_py' has no attribute 'no_such_name'\n"


def test_setup_installed_the_finder_in_this_environment() -> None:
    installed = Path(sysconfig.get_paths()["purelib"]) / PTH_NAME
    assert repr(str(Path(rosidl_import.__file__))) in installed.read_text()


def test_the_pth_file_is_written_whole(tmp_path: Path) -> None:
    written = Path(install_pth(str(tmp_path)))
    assert written == tmp_path / PTH_NAME
    assert written.read_text().count("\n") == 1  # site runs one line per import statement
    assert [p.name for p in tmp_path.iterdir()] == [PTH_NAME]


def test_a_jupyter_server_of_this_environment_builds_no_grammar_at_start() -> None:
    """jsonschema's optional IRI check (rfc3987-syntax) is not installed: 20 MiB, 1 s."""
    program = "import sys, jupyter_server.serverapp; print('lark' in sys.modules)"
    assert _run(program) == "False\n"
