"""The `ros2` console command of the course (JupyterLab terminals): ROS 2 Jazzy's words, faster.

Graph and parameter verbs go to a per-domain daemon holding a warm client node (started on
first use); `ros2 run`, `ros2 pkg` and usage errors run here; `ros2 launch` goes to
course_lib.launch.
"""

from __future__ import annotations

import os
import sys

__all__ = ["main"]


def _terminal_env(domain: str | None) -> dict[str, str]:
    from course_lib.session import session_env

    return session_env(int(domain), os.environ) if domain else dict(os.environ)


def _local(argv: list[str], domain: str | None) -> int:
    """Run the command in this process, printing as it goes."""
    import shutil

    from course_lib.ros2.commands import Context, execute
    from course_lib.ros2.console import StreamingConsole

    def write(stream: str, text: str) -> None:
        target = sys.stdout if stream == "stdout" else sys.stderr
        target.write(text)
        target.flush()

    console = StreamingConsole(write, width=shutil.get_terminal_size().columns)
    ctx = Context(console, _in_process_client, cwd=os.getcwd(), env=_terminal_env(domain))
    return execute(argv, ctx)


def _in_process_client():  # type: ignore[no-untyped-def]
    from course_lib.ros2.api import client

    return client()


def _course_domain() -> str | None:
    """Return the domain of a running `make lab` when the shell sets none (then use it)."""
    from course_lib.lab import running_lab_domain

    domain = running_lab_domain()
    if domain is not None:
        os.environ["ROS_DOMAIN_ID"] = domain
    return domain


def main(argv: list[str] | None = None) -> int:
    """Run `ros2 <argv>` and return its exit code."""
    from course_lib.ros2.table import uses_graph

    argv = list(sys.argv[1:] if argv is None else argv)
    domain = os.environ.get("ROS_DOMAIN_ID", "").strip() or _course_domain()
    # `--stdin` reads this terminal's input, which the daemon does not have: run it here.
    if not uses_graph(argv) or domain is None or "--stdin" in argv:
        return _local(argv, domain)
    from course_lib.ros2.connect import DaemonUnavailable, connect_or_start, request

    try:
        sock = connect_or_start(domain, _terminal_env(domain))
        return request(sock, argv, cwd=os.getcwd(), stdout=sys.stdout, stderr=sys.stderr)
    except DaemonUnavailable:
        return _local(argv, domain)
    except KeyboardInterrupt:
        return 2


if __name__ == "__main__":
    sys.exit(main())
