"""`python -m course_lib <command>`: the course's own utilities behind the Makefile."""

from __future__ import annotations

import argparse
import os
import signal
import sys
from pathlib import Path

__all__ = ["main"]


def _build(args: argparse.Namespace) -> int:
    from .workspace import build_workspace

    parser = argparse.ArgumentParser(prog="python -m course_lib build")
    parser.add_argument("--workspace", type=Path, help="a colcon workspace (default: rosject/)")
    options = parser.parse_args(args.extra)
    if options.workspace is None:
        return build_workspace()
    return build_workspace(workspace=options.workspace.resolve())


def _lab(args: argparse.Namespace) -> int:
    from ..lab.jupyterlab import run_lab

    signal.signal(signal.SIGTERM, signal.default_int_handler)  # stop cleanly on SIGTERM too
    checked = _check_config_in_child()  # a broken config/ stops the lab before JupyterLab starts
    return checked or run_lab(args.extra)


def _check_config_in_child() -> int:
    """Check config/ in a forked child; return 0 if valid, 1 if not (said on stderr), 130 if
    stopped.

    The lab's process lives as long as the lab: the checker's modules (YAML schemas, lesson
    texts, package metadata) would stay in it, about 4 MiB a learner.
    """
    sys.stdout.flush()
    sys.stderr.flush()
    pid = os.fork()
    if pid == 0:  # the child: check, say what is wrong, and leave without Python's exit
        code = 1
        try:
            from ..core.errors import CourseError
            from .config_check import require_valid_config

            try:
                require_valid_config()
                code = 0
            except CourseError as exc:
                print(exc, file=sys.stderr)
        except KeyboardInterrupt:  # Ctrl-C reaches the whole group: the lab says it stopped
            code = 130
        except BaseException:  # a child must never return into the parent's code: say why
            import traceback

            traceback.print_exc()
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os._exit(code)
    try:
        _, status = os.waitpid(pid, 0)
    except KeyboardInterrupt:  # Ctrl-C or SIGTERM to the lab alone: the check ends with it
        from ..core.host.signalling import send

        send(pid, signal.SIGKILL, reason="the lab stopped during its config check")
        os.waitpid(pid, 0)
        return 130
    code = os.waitstatus_to_exitcode(status)
    return code if code in (0, 130) else 1


def _hub(args: argparse.Namespace) -> int:
    from ..hub.launcher import run_hub
    from ..hub.provision.settings import HUB_YAML

    parser = argparse.ArgumentParser(prog="python -m course_lib hub")
    parser.add_argument("--config", type=Path, default=HUB_YAML, help="the class's hub.yaml")
    return run_hub(parser.parse_args(args.extra).config)


def _hub_lab(args: argparse.Namespace) -> int:
    from ..hub.singleuser import run_hub_lab

    return run_hub_lab(args.extra)


def _image(args: argparse.Namespace) -> int:
    from .image_entry import main as image_main

    return image_main(args.extra)


def _notebooks(args: argparse.Namespace) -> int:
    from .notebook_outputs import refresh_notebooks

    return refresh_notebooks(args.extra)


def _check_config(args: argparse.Namespace) -> int:
    from .config_check import check_config

    parser = argparse.ArgumentParser(
        prog="python -m course_lib check-config",
        description="Check every file of config/ alone and together; exit 1 on any problem.",
    )
    parser.add_argument("--config", type=Path, help="another folder of instructor YAML")
    parser.add_argument(
        "--write-comments",
        action="store_true",
        help="rewrite the files' comments from the schema, keeping their values",
    )
    options = parser.parse_args(args.extra)
    folder = options.config.resolve() if options.config else None
    if options.write_comments:
        from .config_check import write_comments

        for path in write_comments(folder):
            print(f"rewrote the comments of {path.name}")
    report = check_config(folder)
    print(report.render(), file=sys.stdout if report.ok else sys.stderr)
    return 0 if report.ok else 1


def _doctor(_args: argparse.Namespace) -> int:
    from .config_check import check_config
    from .doctor import install_checks, report

    checked = check_config()
    print(checked.render())
    checks = install_checks()
    print(report(checks))
    broken = [check.name for check in checks if not check.ok]
    if broken:
        print(f"The install is broken ({', '.join(broken)}): `make setup` repairs it.",
              file=sys.stderr)  # fmt: skip
    return 0 if checked.ok and not broken else 1


def _stop(args: argparse.Namespace) -> int:
    from .stop import stop_all

    parser = argparse.ArgumentParser(
        prog="python -m course_lib stop",
        description="Stop the course processes this clone started (labs, simulations, 3D "
        "views, nodes, ros2 daemons), like Ctrl-C, then harder; say what stopped. A learner's "
        "own programs and other clones' course processes keep running and are listed.",
    )
    parser.add_argument(
        "--all", action="store_true", help="stop the course processes of every clone too"
    )
    options = parser.parse_args(args.extra)  # an unknown argument: the usage, nothing stopped
    report = stop_all(everything=options.all)
    print(report.render())
    return 1 if report.left else 0


COMMANDS = {
    "build": (_build, "build the ROS workspace in rosject/ with colcon"),
    "lab": (_lab, "start JupyterLab on the first lesson"),
    "hub": (_hub, "start the class's JupyterHub (config/hub.yaml; as root)"),
    "hub-lab": (_hub_lab, "a learner's server on the class hub (started by the hub)"),
    "image": (_image, "the course's image: a learner's lab, or the command given (Dockerfile)"),
    "notebooks": (_notebooks, "re-execute the notebooks to refresh their stored outputs"),
    "check-config": (_check_config, "check every file of config/, alone and together"),
    "doctor": (_doctor, "say what is installed and which course processes run"),
    "stop": (_stop, "stop this user's course processes (labs, simulations, nodes, daemons)"),
}


def main(argv: list[str] | None = None) -> int:
    """Run one course command."""
    parser = argparse.ArgumentParser(prog="python -m course_lib")
    sub = parser.add_subparsers(dest="command", required=True)
    for name, (func, summary) in COMMANDS.items():
        # add_help=False: `-h` reaches the command itself (its own options, or jupyter lab's)
        sub.add_parser(name, help=summary, add_help=False).set_defaults(func=func)
    args, extra = parser.parse_known_args(argv)
    args.extra = extra  # passed through to jupyter lab, the hub or the notebooks' refresh
    from ..core.errors import CourseError

    try:
        return int(args.func(args))
    except CourseError as exc:  # expected problems (a runtime folder not private...): no traceback
        print(exc, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
