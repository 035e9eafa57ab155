"""The terminal's `ros2`, started once: hand the command to the lab's daemon, print its answer.

The ROS wheels re-execute every Python that starts with its site-packages (to set the
library path rclpy needs), so a plain console script starts Python twice. The launcher
that `make setup` installs as the venv's `ros2` (`install_launcher`) starts Python with
`-S` instead: no site-packages, no re-execution, and this module imports only the socket
and JSON modules (no pathlib, no typing). Commands the daemon serves (node, param, topic,
service, interface and the reading pkg verbs) go to the daemon of the command's domain;
everything else, and every command when no daemon answers, goes to the full command
(course_lib.ros2.command.cli, started as a console script is), which starts the daemon when
a graph verb needs it.
"""

from __future__ import annotations

import os
import sys

TYPE_CHECKING = False  # typing is not imported: this module is the terminal's `ros2`
if TYPE_CHECKING:
    from pathlib import Path

__all__ = ["daemon_serves", "install_launcher", "main", "maybe_own_node_option"]

# Commands the daemon runs for a terminal (None: every verb; else the verbs it runs).
# `run`, `launch` and `daemon` act in the terminal itself; `pkg create` writes files.
SERVED: dict[str, frozenset[str] | None] = {
    "node": None,
    "param": None,
    "service": None,
    "topic": None,
    "interface": None,
    "pkg": frozenset({"executables", "list", "prefix", "xml"}),
}
TOP_LEVEL_OPTION = "--use-python-default-buffering"
# Set (to anything) so that a command the daemon should serve fails instead of falling back.
NO_FALLBACK_ENV = "COURSE_ROS2_NO_FALLBACK"
NO_FALLBACK_EXIT = 70
FULL_COMMAND = "course_lib.ros2.command.cli"


def maybe_own_node_option(word: str) -> bool:
    """Return whether `word` may be --no-daemon or -s/--use-sim-time, abbreviated or grouped."""
    if word.startswith("--"):
        return len(word) > 4 and (
            "--no-daemon".startswith(word) or "--use-sim-time".startswith(word)
        )
    return word.startswith("-") and word[1:].isalpha() and "s" in word


def daemon_serves(argv: list[str]) -> bool:
    """Return whether a terminal's daemon runs this command line (else the terminal does)."""
    words = [w for w in argv if w != TOP_LEVEL_OPTION]
    if not words or words[0].startswith("-") or words[0] not in SERVED:
        return False
    if "--stdin" in argv or any(maybe_own_node_option(w) for w in words):
        return False  # the terminal's input, or a node of the command's own
    verbs = SERVED[words[0]]
    return verbs is None or (len(words) > 1 and words[1] in verbs)


def _domain() -> str | None:
    domain = os.environ.get("ROS_DOMAIN_ID", "").strip()
    if domain:
        return domain
    from ...processes.lab_markers import running_lab_domain

    return running_lab_domain()


def _full(argv: list[str]) -> int:
    """Replace this process by the full command (its Python re-executes as the wheels want)."""
    sys.stdout.flush()
    sys.stderr.flush()
    os.execv(sys.executable, [sys.executable, "-P", "-m", FULL_COMMAND, *argv])
    return 1  # not reached


def main(argv: list[str] | None = None) -> int:
    """Run `ros2 <argv>` through the daemon, or through the full command."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if not daemon_serves(argv):
        return _full(argv)
    from ..node.wire import DaemonUnavailable, connect, daemon_socket, request

    try:
        domain = _domain()
        if domain is None:
            return _full(argv)
        sock = connect(daemon_socket(domain))
    except (DaemonUnavailable, OSError, ValueError):
        if os.environ.get(NO_FALLBACK_ENV):
            sys.stderr.write("ros2: no daemon answers (and the fallback is off)\n")
            return NO_FALLBACK_EXIT
        return _full(argv)
    env = {**os.environ, "ROS_DOMAIN_ID": domain}
    try:
        return request(sock, argv, cwd=os.getcwd(), stdout=sys.stdout, stderr=sys.stderr, env=env)
    except DaemonUnavailable:
        return _full(argv)
    except KeyboardInterrupt:
        return 2  # as the full command (and ros2cli: signal.SIGINT)


LAUNCHER = """#!{python} -S
# The course's `ros2`, written by `make setup`: one Python start (course_lib.ros2.command.quick).
import sys
sys.path.insert(0, {root!r})
from course_lib.ros2.command.quick import main
sys.exit(main())
"""


def install_launcher(bin_dir: str | Path | None = None) -> Path:
    """Write the `ros2` launcher into the venv's bin folder (replacing the console script)."""
    from pathlib import Path

    from ...core.files.atomic_files import atomic_write
    from ...core.paths import REPO_ROOT, venv_bin_dir

    folder = Path(bin_dir) if bin_dir else venv_bin_dir()
    python = folder / "python"
    target = folder / "ros2"
    text = LAUNCHER.format(python=python, root=str(REPO_ROOT))
    atomic_write(target, text)
    target.chmod(0o755)
    return target


if __name__ == "__main__":
    if sys.argv[1:] == ["--install-launcher"]:
        print(install_launcher())
        raise SystemExit(0)
    raise SystemExit(main())
