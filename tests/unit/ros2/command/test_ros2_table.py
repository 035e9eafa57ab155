"""The one table of verbs: every entry resolves, help lists only what works, the rest refuses."""

from __future__ import annotations

import pytest

from course_lib.ros2.command import table
from course_lib.ros2.command.commands import run_collected

ENTRIES = [
    (name, verb_name, verb)
    for name, command in table.COMMANDS.items()
    for verb_name, verb in (
        {**(command.verbs or {}), "": command.own} if command.own else (command.verbs or {})
    ).items()
]


@pytest.mark.parametrize(("command", "verb", "entry"), ENTRIES)
def test_every_entry_resolves(command: str, verb: str, entry: table.Verb) -> None:
    assert callable(table.resolve(entry.handler))
    if entry.arguments:
        assert callable(table.resolve(entry.arguments))


def test_top_level_help_lists_only_the_course_commands() -> None:
    out = run_collected(["--help"])
    assert out.exit_code == 0
    listed = [
        line.split()[0]
        for line in out.stdout.split("Commands:\n", 1)[1].splitlines()
        if line.startswith("  ") and not line.startswith("   ") and "Call `" not in line
    ]
    assert listed == sorted(table.COMMANDS)
    for absent in ("action", "doctor", "bag", "wtf"):
        assert f"  {absent} " not in out.stdout


@pytest.mark.parametrize(
    "argv",
    [
        ["action"],
        ["action", "list", "-t"],
        ["doctor", "--report"],
        ["bag", "record", "/cmd_vel"],
        ["lifecycle", "get", "/n"],
        ["wtf"],
        ["multicast", "receive"],
        ["component", "list"],
    ],
)
def test_absent_commands_say_what_to_use(argv: list[str]) -> None:
    out = run_collected(argv)
    assert (out.stdout, out.exit_code) == ("", 1)
    first, has = out.stderr.splitlines()
    assert first.startswith(f"`ros2 {argv[0]}` is not part of this course's ros2. ")
    assert first.endswith(table.ELSEWHERE[argv[0]])
    assert has == (
        f"This course's ros2 has: {', '.join(sorted(table.COMMANDS))} (see `ros2 --help`)."
    )


@pytest.mark.parametrize("argv", [["pkg", "list"], ["service", "echo", "/s"]])
def test_absent_verbs_say_what_to_use(argv: list[str]) -> None:
    out = run_collected(argv)
    assert out.exit_code == 1
    assert out.stderr.startswith(f"`ros2 {argv[0]} {argv[1]}` is not part of this course's ros2.")


@pytest.mark.parametrize("argv", [["servce"], ["servce", "list", "-t"]])
def test_unknown_command_suggests_the_closest(argv: list[str]) -> None:
    out = run_collected(argv)
    assert out.exit_code == 2
    assert out.stderr.startswith("ros2: unknown command 'servce'. Did you mean `ros2 service`?\n")


def test_terminal_routing_follows_the_table() -> None:
    assert table.uses_graph(["param", "get", "/n", "v"])
    assert table.uses_graph(["topic", "--include-hidden-topics", "list"])
    assert not table.uses_graph(["pkg", "prefix", "x"])
    assert not table.uses_graph(["run", "p", "e"])
    assert not table.uses_graph(["launch", "p", "f"])
    assert not table.uses_graph(["action", "list"])


def test_verb_help_lists_only_the_course_verbs() -> None:
    out = run_collected(["pkg", "-h"])
    assert out.exit_code == 0
    assert "executables" in out.stdout and "prefix" in out.stdout and "create" in out.stdout
    assert "xml" not in out.stdout
    topic = run_collected(["topic", "--help"]).stdout
    for verb in ("bw", "delay", "echo", "find", "hz", "info", "list", "pub", "type"):
        assert f"\n    {verb} " in topic or f"\n  {verb} " in topic, verb


@pytest.mark.parametrize(
    "argv",
    [
        ["topic", "hz", "/cmd_vel", "-s"],
        ["topic", "bw", "/cmd_vel", "--use-sim-time"],
        ["topic", "echo", "/cmd_vel", "-s", "--timeout", "2"],
    ],
)
def test_flags_the_course_cannot_honour_are_refused(argv: list[str]) -> None:
    out = run_collected(argv)
    assert out.exit_code == 1
    assert "is not part of this course" in out.stderr


def test_package_exports_are_not_shadowed_by_modules() -> None:
    """A verb module named like an exported function would replace it once imported."""
    import importlib
    import pkgutil

    import course_lib.ros2 as package

    for info in pkgutil.walk_packages(package.__path__, "course_lib.ros2."):
        # `python -m course_lib.ros2.command.daemon` serves forever
        if info.name != "course_lib.ros2.command.daemon":
            importlib.import_module(info.name)
    for name in package.__all__:
        assert not isinstance(getattr(package, name), type(package)), name
