"""The `ros2` console command of the course (JupyterLab terminals): ROS 2 Jazzy's words, faster.

Graph and parameter verbs go to a per-domain daemon holding a warm client node (started on
first use); with `--no-daemon` or `--use-sim-time` they run here on a node of this command's
own (`_ros2cli_<pid>`), as ros2cli's do, and no daemon is started. `ros2 run`, `ros2 pkg`,
`ros2 daemon` and usage errors run here; `ros2 launch` goes to course_lib.launch.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable

TYPE_CHECKING = False  # as typing's, without importing typing: the terminal's `ros2` starts light
if TYPE_CHECKING:
    from course_lib.ros2.node.client import RosClient

__all__ = ["main"]


def _terminal_env(domain: str | None) -> dict[str, str]:
    """Return the caller's environment with the course's settings and workspace underlaid."""
    from course_lib.core.ament import workspace_env
    from course_lib.session.session import session_env

    return session_env(int(domain), os.environ) if domain else workspace_env(os.environ)


def _local(argv: list[str], domain: str | None, *, direct: bool = False) -> int:
    """Run the command in this process, printing as it goes (on a node of its own if direct)."""
    import shutil

    from course_lib.ros2.command.commands import Context, command_of, execute
    from course_lib.ros2.verbkit.console import StreamingConsole

    def write(stream: str, text: str) -> None:
        target = sys.stdout if stream == "stdout" else sys.stderr
        target.write(text)
        target.flush()

    console = StreamingConsole(write, width=shutil.get_terminal_size().columns)
    env = _terminal_env(domain)
    if command_of(argv) == "launch":  # launch resolves packages through this process's env
        from course_lib.ros2.verbs.launch import launch_env

        words = argv[argv.index("launch") + 1 :]
        env = launch_env(words, os.environ, env)
        os.environ.update(env)
    factory = _direct_client(argv, env) if direct else _in_process_client
    ctx = Context(console, factory, cwd=os.getcwd(), env=env)
    return execute(argv, ctx)


def _direct_client(argv: list[str], env: dict[str, str]) -> Callable[[], RosClient]:
    """Return a factory of a client on a node of this command's own (closed at exit)."""

    def make() -> RosClient:
        import atexit

        from course_lib.ros2.node.direct import DirectNode

        os.environ.update(env)  # this process's participant: the course's discovery settings
        sim_time = _own_node_options(argv)[1]
        node = DirectNode(domain_id=int(env["ROS_DOMAIN_ID"]), use_sim_time=sim_time)
        atexit.register(node.close_at_exit)
        return node.client()

    return make


def _own_node_options(argv: list[str]) -> tuple[bool, bool]:
    """Return (--no-daemon, --use-sim-time) as ros2cli parses argv (free when neither is given)."""
    from course_lib.ros2.command.quick import maybe_own_node_option

    if not any(maybe_own_node_option(word) for word in argv):
        return False, False
    from course_lib.ros2.command import parsers

    token = parsers.output_sink.set(parsers._Sink())
    try:
        args, _parser = parsers.parse(list(argv))
    except parsers.ParseExit:
        return False, False  # the usage error is printed where the command runs
    finally:
        parsers.output_sink.reset(token)
    return bool(getattr(args, "no_daemon", False)), bool(getattr(args, "use_sim_time", False))


def _in_process_client() -> RosClient:
    from course_lib.ros2.node.session_client import client

    return client()


def _course_domain() -> str | None:
    """Return the domain of a running `make lab` when the shell sets none (then use it)."""
    from course_lib.processes.lab_markers import running_lab_domain

    domain = running_lab_domain()
    if domain is not None:
        os.environ["ROS_DOMAIN_ID"] = domain
    return domain


def main(argv: list[str] | None = None) -> int:
    """Run `ros2 <argv>` and return its exit code (requests tagged as the terminal's)."""
    from course_lib.core.param_journal import acting_door

    with acting_door("terminal"):
        return _main(argv)


def _main(argv: list[str] | None) -> int:
    from course_lib.ros2.command.table import uses_graph

    argv = list(sys.argv[1:] if argv is None else argv)
    domain = os.environ.get("ROS_DOMAIN_ID", "").strip() or _course_domain()
    # `--stdin` reads this terminal's input, which the daemon does not have: run it here.
    if not uses_graph(argv) or domain is None or "--stdin" in argv:
        return _local(argv, domain)
    if any(_own_node_options(argv)):
        return _local(argv, domain, direct=True)
    from course_lib.ros2.node.connect import DaemonUnavailable, connect_or_start, request

    try:
        sock = connect_or_start(domain, _terminal_env(domain))
        return request(sock, argv, cwd=os.getcwd(), stdout=sys.stdout, stderr=sys.stderr)
    except DaemonUnavailable:
        return _local(argv, domain)
    except KeyboardInterrupt:
        return 2


if __name__ == "__main__":
    sys.exit(main())
