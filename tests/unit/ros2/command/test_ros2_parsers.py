"""Bad command lines get argparse's usage text and exit 2, as with ros2cli."""

from __future__ import annotations

from course_lib.ros2.command.commands import run_collected


def test_missing_arguments_print_usage_and_exit_2() -> None:
    out = run_collected(["param", "get"])
    assert out.exit_code == 2
    assert out.stdout == ""
    assert out.stderr == (
        "usage: ros2 param get [-h] [--spin-time SPIN_TIME] [-s] [--no-daemon]\n"
        "                      [--include-hidden-nodes] [--hide-type] [--timeout N]\n"
        "                      node_name parameter_name\n"
        "ros2 param get: error: the following arguments are required: node_name, "
        "parameter_name\n"
    )


def test_unknown_verb_lists_the_real_verbs() -> None:
    out = run_collected(["param", "bogus"])
    assert out.exit_code == 2
    assert out.stderr.endswith(
        "invalid choice: 'bogus' (choose from 'delete', 'describe', 'dump', 'get', 'list', "
        "'load', 'set')\n"
    )


def test_unknown_command_and_flag() -> None:
    assert run_collected(["foo"]).exit_code == 2
    out = run_collected(["node", "list", "--bogus"])
    assert (out.exit_code, out.stderr.splitlines()[-1]) == (
        2,
        "ros2: error: unrecognized arguments: --bogus",
    )


def test_help_goes_to_stdout_with_exit_0() -> None:
    out = run_collected(["param", "set", "-h"])
    assert out.exit_code == 0
    assert out.stdout.startswith("usage: ros2 param set [-h]")
    assert "Set parameter\n" in out.stdout
    bare = run_collected(["param"])
    assert bare.exit_code == 0
    assert "  get       Get parameter\n" in bare.stdout


def test_accepts_the_real_tools_common_flags() -> None:
    from course_lib.ros2.command import parsers

    sink = parsers._Sink()
    token = parsers.output_sink.set(sink)
    try:
        args, _ = parsers.parse(
            [
                "param",
                "get",
                "/n",
                "v",
                "--no-daemon",
                "--spin-time",
                "2",
                "-s",
                "--include-hidden-nodes",
                "--timeout",
                "3",
            ]
        )
    finally:
        parsers.output_sink.reset(token)
    assert (args.no_daemon, args.spin_time, args.use_sim_time, args.timeout) == (
        True,
        2.0,
        True,
        3,
    )


def test_usage_wraps_to_the_terminal_width() -> None:
    narrow = run_collected(["param", "get"], width=60).stderr
    assert max(len(line) for line in narrow.splitlines()[:-1]) <= 58


def test_a_command_line_given_again_parses_and_prints_the_same() -> None:
    """Parser trees are kept by command line: the same line gives the same namespace, usage,
    errors and help again (help at the width of the console asking), other lines their own."""
    from course_lib.ros2.command import parsers

    lines = [
        ["param", "get", "/param_vel_node", "velocity"],
        ["param", "get"],
        ["param", "bogus"],
        ["node", "list", "--bogus"],
        ["param", "set", "-h"],
        ["param"],
        ["param", "get", "/other", "speed", "--hide-type"],
    ]
    first = [run_collected(line) for line in lines]
    again = [run_collected(line) for line in reversed(lines)][::-1]
    assert [(o.exit_code, o.stdout, o.stderr) for o in again] == [
        (o.exit_code, o.stdout, o.stderr) for o in first
    ]
    args, _ = parsers.parse(["param", "get", "/param_vel_node", "velocity"])
    other, _ = parsers.parse(["param", "get", "/other", "speed", "--hide-type"])
    assert (args.node_name, args.parameter_name, args.hide_type) == (
        "/param_vel_node",
        "velocity",
        False,
    )
    assert (other.node_name, other.parameter_name, other.hide_type) == ("/other", "speed", True)

    def help_at(width: int) -> str:
        sink = parsers._Sink(width=width)
        token = parsers.output_sink.set(sink)
        try:
            parsers.parse(["param", "set", "-h"])
        except parsers.ParseExit:
            pass
        finally:
            parsers.output_sink.reset(token)
        return "".join(sink.stdout)

    kept = help_at(40)  # the tree was built for an 80-column console above
    parsers._trees.clear()
    assert kept == help_at(40) != first[4].stdout
