"""What `make setup` keeps out of every process: code generators and grammars built at import."""

from __future__ import annotations

import ast
import importlib.machinery
import importlib.util
import json
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

from course_lib.tools import slim_imports
from course_lib.tools.slim_imports import PTH_NAME, install_pth

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


def test_the_simulations_view_never_loads_ipython_or_pillow() -> None:
    """meshcat's __init__ imports its notebook visualizer: IPython and Pillow, 6 MiB."""
    program = """
import json, sys, mujoco
from course_lib.sim.view.live import LiveView
from course_lib.sim.world.model import build_model
from course_lib.viz.server import serve_in_thread
server = serve_in_thread([])
model = build_model()
data = mujoco.MjData(model)
view = LiveView(server.zmq_url, model, data)
assert view.update(data)
view.close()
server.stop()
print(json.dumps(sorted({m.split(".")[0] for m in sys.modules} & {"IPython", "PIL"})))
"""
    assert json.loads(_run(program)) == []


def _names_bound_by(init: Path) -> set[str]:
    """The public names a package's own __init__ binds from its modules, or defines."""
    names: set[str] = set()
    body = list(ast.parse(init.read_text()).body)
    while body:
        node = body.pop()
        if isinstance(node, ast.Try):
            body += node.body  # what the package binds when its optional parts import
        elif isinstance(node, ast.ImportFrom) and node.level == 1:  # from . / from .x import
            names |= {alias.asname or alias.name for alias in node.names}
        elif isinstance(node, ast.FunctionDef | ast.ClassDef):
            names.add(node.name)
    return {name for name in names if not name.startswith("_")}


@pytest.mark.parametrize("package", sorted(slim_imports.SLIM_PACKAGES))
def test_a_slim_package_binds_every_name_its_own_init_binds(package: str) -> None:
    """Fails when an upgrade of the package binds a name the finder's table does not know."""
    spec = importlib.machinery.PathFinder.find_spec(package)
    assert spec is not None and spec.origin is not None
    assert _names_bound_by(Path(spec.origin)) <= set(slim_imports.SLIM_PACKAGES[package])


def test_meshcat_still_binds_every_name_of_its_init() -> None:
    program = """
import os, meshcat
from meshcat import Visualizer
from meshcat.visualizer import Visualizer as same
assert Visualizer is same and meshcat.Visualizer is same
assert meshcat.geometry.Box and meshcat.transformations.identity_matrix().shape == (4, 4)
assert meshcat.commands and meshcat.servers and meshcat.animation and meshcat.visualizer
assert os.path.isfile(os.path.join(meshcat.viewer_assets_path(), "dist", "main.min.js"))
try:
    meshcat.no_such_name
except AttributeError as error:
    print(error)
"""
    assert _run(program) == "module 'meshcat' has no attribute 'no_such_name'\n"


def test_an_interface_package_loads_only_the_interfaces_used() -> None:
    program = """
import json, sys
from geometry_msgs.msg import Twist
import geometry_msgs.msg as package
Twist(linear=package.Vector3(x=0.2))
loaded = sorted(m for m in sys.modules if m.startswith("geometry_msgs.msg."))
names = [n for n in dir(package) if not n.startswith("_")]
print(json.dumps([loaded, "PoseWithCovariance" in names, len(names), "numpy" in sys.modules]))
"""
    loaded, listed, count, numpy = json.loads(_run(program))
    assert loaded == ["geometry_msgs.msg._twist", "geometry_msgs.msg._vector3"]
    assert listed and count == 32  # dir() still lists every message of the package
    assert not numpy  # only the covariance messages need it


def test_a_node_serving_and_calling_parameter_services_never_loads_numpy() -> None:
    """Every Jazzy service type carries ServiceEventInfo (a uint8[16]), whose generated module
    imports numpy: `param_vel`, each kernel and each daemon paid 10 MiB for it."""
    program = """
import json, sys
import rclpy
from rcl_interfaces.srv import GetParameters
rclpy.init()
node = rclpy.create_node("numpy_probe")
node.declare_parameter("velocity", 0.2)
client = node.create_client(GetParameters, "/numpy_probe/get_parameters")
assert client.wait_for_service(10.0)
future = client.call_async(GetParameters.Request(names=["velocity"]))
rclpy.spin_until_future_complete(node, future, timeout_sec=10.0)
print(json.dumps([future.result().values[0].double_value, "numpy" in sys.modules]))
node.destroy_node()
rclpy.shutdown()
"""
    value, numpy = json.loads(_run(program))
    assert value == 0.2
    assert not numpy, "a node with parameter services loaded numpy"


def test_a_message_with_a_fixed_size_array_loads_numpy_when_built() -> None:
    program = """
import json, sys
from geometry_msgs.msg import PoseWithCovariance
import geometry_msgs.msg._pose_with_covariance as module
before = "numpy" in sys.modules
pose = PoseWithCovariance()
pose.covariance[35] = 2.5
import numpy
ones = [1.0] * 36
equal = PoseWithCovariance(covariance=ones) == PoseWithCovariance(covariance=ones)
print(json.dumps([before, module.numpy is numpy, float(pose.covariance.sum()), equal]))
"""
    before, bound, total, equal = json.loads(_run(program))
    assert not before  # imported, not built: numpy waits
    assert bound  # once used, the module's numpy is numpy itself (no stand-in in the way)
    assert total == 2.5 and equal


def test_a_generated_module_keeps_its_line_numbers() -> None:
    """A traceback through a generated module points at the line that raised it."""
    program = """
import traceback
from geometry_msgs.msg import PoseWithCovariance
import geometry_msgs.msg._pose_with_covariance as module
assert type(module.__spec__.loader).__name__ == "_OnFirstUseLoader"  # the module rewritten
try:
    PoseWithCovariance(covariance=["not a number"] * 36)
except ValueError:
    frame = traceback.extract_tb(__import__("sys").exc_info()[2])[-1]
    print(frame.lineno, frame.line)
"""
    lineno, line = _run(program).strip().split(" ", 1)
    source = Path(importlib.util.find_spec("geometry_msgs.msg._pose_with_covariance").origin)
    assert source.read_text().splitlines()[int(lineno) - 1].strip() == line.strip()


def test_an_interface_package_binds_every_name_as_its_generated_init() -> None:
    program = """
from geometry_msgs.msg import *
import geometry_msgs.msg, rosidl_adapter.msg
from geometry_msgs.msg._pose_with_covariance import PoseWithCovariance as same
assert PoseWithCovariance is same and geometry_msgs.msg.Twist is Twist
assert "_twist" not in dir()  # a star import binds the messages, not their modules
assert rosidl_adapter.msg.convert_msg_to_idl  # an __init__ of its own runs as written
try:
    geometry_msgs.msg.NoSuchMessage
except AttributeError as error:
    print(error)
"""
    assert _run(program) == "module 'geometry_msgs.msg' has no attribute 'NoSuchMessage'\n"


def test_jupyterlab_never_loads_httpxs_command_line_client() -> None:
    """JupyterLab's extension manager imports httpx, whose __init__ imports its CLI: 4 MiB."""
    program = "import sys, jupyterlab.labapp; print(sorted({'rich', 'click'} & set(sys.modules)))"
    assert _run(program) == "[]\n"


def test_jupyterlab_never_loads_aiohttp_for_its_proxy() -> None:
    """jupyter-server-proxy's handlers import aiohttp (and aiodns, yarl, multidict, ...) only
    to probe processes it would start itself: 8.5 MiB in every learner's server."""
    program = """
import json, sys
import jupyter_server_proxy.handlers as handlers
print(json.dumps([sorted({"aiohttp", "aiodns", "yarl"} & set(sys.modules)),
                  type(handlers.aiohttp).__name__]))
"""
    loaded, stand_in = json.loads(_run(program))
    assert loaded == [], f"the proxy's handlers loaded {loaded}"
    assert stand_in == "_ImportOnFirstUse"


def test_the_proxys_aiohttp_still_loads_on_first_use() -> None:
    program = """
import sys
import jupyter_server_proxy.handlers as handlers
import aiohttp
connector = handlers.aiohttp.ClientConnectionError
print(connector is aiohttp.ClientConnectionError, handlers.aiohttp is aiohttp)
"""
    assert _run(program) == "True True\n"


def test_httpxs_command_line_client_still_runs() -> None:
    program = """
import sys, httpx
loaded = []
for _ in range(2):
    sys.argv = ["httpx", "--help"]
    try:
        httpx.main()
    except SystemExit as end:
        print("exit", end.code)
    loaded.append(sys.modules["httpx._main"])
print("loaded once:", loaded[0] is loaded[1])
"""
    printed = _run(program)
    assert "Usage: httpx <URL> [OPTIONS]" in printed
    assert printed.endswith("exit 0\nloaded once: True\n")


def test_the_finder_adds_no_import_to_the_start_of_python() -> None:
    """It runs in every start of the environment (every `ros2` command, every node)."""
    assert _run("import sys; print('typing' in sys.modules)") == "False\n"


def test_setup_installed_the_finder_in_this_environment() -> None:
    installed = Path(sysconfig.get_paths()["purelib"]) / PTH_NAME
    assert repr(str(Path(slim_imports.__file__))) in installed.read_text()


def test_the_pth_file_is_written_whole(tmp_path: Path) -> None:
    written = Path(install_pth(str(tmp_path)))
    assert written == tmp_path / PTH_NAME
    assert written.read_text().count("\n") == 1  # site runs one line per import statement
    assert [p.name for p in tmp_path.iterdir()] == [PTH_NAME]


def test_setup_removes_the_finder_file_of_earlier_versions(tmp_path: Path) -> None:
    (tmp_path / "rosidl_import.pth").write_text("import sys\n")
    install_pth(str(tmp_path))
    assert [p.name for p in tmp_path.iterdir()] == [PTH_NAME]


def test_a_jupyter_server_of_this_environment_builds_no_grammar_at_start() -> None:
    """jsonschema's optional IRI check (rfc3987-syntax) is not installed: 20 MiB, 1 s."""
    program = "import sys, jupyter_server.serverapp; print('lark' in sys.modules)"
    assert _run(program) == "False\n"
