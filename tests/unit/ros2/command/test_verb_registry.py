"""One way to register a verb: declared beside its handler, indexed once, nothing forgotten."""

from __future__ import annotations

import importlib
import inspect
import json
import shlex
from pathlib import Path

import pytest

from course_lib.ros2.command import index_builder, table
from course_lib.ros2.verbkit import registry

GOLDEN = Path(__file__).resolve().parents[3] / "golden" / "ros2"

# The verbs of ROS 2 Jazzy's `ros2` that the course offers ("" for `ros2 run` itself).
JAZZY_VERBS = {
    "daemon": {"start", "status", "stop"},
    "interface": {"list", "package", "packages", "proto", "show"},
    "node": {"info", "list"},
    "param": {"delete", "describe", "dump", "get", "list", "load", "set"},
    "pkg": {"create", "executables", "prefix"},
    "run": {""},
    "service": {"call", "find", "info", "list", "type"},
    "topic": {"bw", "delay", "echo", "find", "hz", "info", "list", "pub", "type"},
}
RAW_COMMANDS = {"launch"}


def test_the_index_is_written_from_the_declarations() -> None:
    written = index_builder.INDEX_PATH.read_text()
    assert written == index_builder.index_text(), (
        f"{index_builder.INDEX_PATH.name} differs from the verbs' declarations: "
        f"run `{index_builder.REWRITE}`"
    )


def test_every_jazzy_verb_is_registered_exactly_once() -> None:
    commands, verbs = index_builder.declarations()
    declared: dict[str, set[str]] = {}
    for command, name in verbs:
        declared.setdefault(command, set()).add(name)
    assert declared == JAZZY_VERBS
    assert set(commands) == set(JAZZY_VERBS) | RAW_COMMANDS
    handlers = [v.handler for v in verbs.values()] + [c.raw for c in commands.values() if c.raw]
    assert len(handlers) == len(set(handlers)), "one handler registered as two verbs"


def _public_functions(module: object) -> dict[str, object]:
    return {
        name: value
        for name, value in vars(module).items()
        if inspect.isfunction(value)
        and value.__module__ == module.__name__  # type: ignore[attr-defined]
        and not name.startswith("_")
    }


def _parameters(function: object) -> list[str]:
    return list(inspect.signature(function).parameters)  # type: ignore[arg-type]


@pytest.mark.parametrize("module_name", index_builder.verb_modules())
def test_no_handler_or_builder_is_left_unregistered(module_name: str) -> None:
    """A verb module's `handler(args, ctx)` and `builder(parser)` are each registered."""
    commands, verbs = index_builder.declarations()
    registered = {v.handler for v in verbs.values()} | {v.arguments for v in verbs.values()}
    registered |= {c.options for c in commands.values()} | {c.raw for c in commands.values()}
    module = importlib.import_module(module_name)
    short = module_name.removeprefix("course_lib.ros2.")
    for name, function in _public_functions(module).items():
        parameters = _parameters(function)
        if parameters in (["args", "ctx"], ["argv", "ctx"], ["parser"]):
            assert f"{short}:{name}" in registered, (
                f"{module_name}.{name} looks like a verb's handler or arguments but no "
                "`command`/`@verb` declaration names it"
            )


def test_every_registration_names_a_function_of_a_verb_module() -> None:
    """The reverse: each declared handler and builder exists where the index says."""
    commands, verbs = index_builder.declarations()
    names = [n for v in verbs.values() for n in (v.handler, v.arguments) if n]
    names += [n for c in commands.values() for n in (c.options, c.raw) if n]
    for name in names:
        assert name.startswith("verbs."), name
        function = table.resolve(name)
        assert callable(function), name
        expected = ["parser"] if name.endswith("arguments") else None
        if expected:
            assert _parameters(function) == expected, name


def _golden_commands() -> list[str]:
    cases = []
    for file in ("cases.json", "cases_part2.json"):
        cases += [case["command"] for case in json.loads((GOLDEN / file).read_text())]
    return sorted({line for line in cases if line.startswith("ros2 ")})  # not the node starts


@pytest.mark.parametrize("line", _golden_commands())
def test_each_golden_transcript_command_resolves(line: str) -> None:
    command, verb = table.verb_of(shlex.split(line)[1:])
    assert command in table.COMMANDS, line
    entry = table.COMMANDS[command]
    if entry.raw is not None:
        handler = entry.raw
    elif entry.own is not None:
        handler = entry.own.handler
    else:
        assert entry.verbs is not None and verb in entry.verbs, line
        handler = entry.verbs[verb].handler
    assert callable(table.resolve(handler))


def _fake(name: str, module: str = "course_lib.ros2.verbs.fake"):  # type: ignore[no-untyped-def]
    def handler(args, ctx):  # type: ignore[no-untyped-def]
        return 0

    handler.__module__ = module
    handler.__qualname__ = name
    return handler


@pytest.fixture
def empty_registry(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(registry, "_commands", {})
    monkeypatch.setattr(registry, "_verbs", {})


@pytest.mark.usefixtures("empty_registry")
def test_a_verb_declared_twice_is_refused_but_a_reimport_is_not() -> None:
    first = _fake("first")
    registry.verb("param", "set", "Set parameter")(first)
    registry.verb("param", "set", "Set parameter")(first)  # a re-imported module: the same
    with pytest.raises(registry.DeclarationError, match="`ros2 param set` is declared twice"):
        registry.verb("param", "set", "Set parameter")(_fake("second"))
    registry.command("param", "Various param related sub-commands")
    with pytest.raises(registry.DeclarationError, match="`ros2 param` is declared twice"):
        registry.command("param", "Other words")
    assert list(registry.declared_verbs()) == [("param", "set")]


@pytest.mark.usefixtures("empty_registry")
def test_a_handler_outside_course_lib_ros2_is_refused() -> None:
    with pytest.raises(registry.DeclarationError, match=r"not in course_lib\.ros2"):
        registry.verb("param", "set", "Set parameter")(_fake("x", module="elsewhere"))


def test_what_the_terminals_daemon_serves_is_declared() -> None:
    """quick.SERVED (the daemon's commands, read without importing the table) names real verbs."""
    from course_lib.ros2.command.quick import SERVED

    for command, verbs in SERVED.items():
        assert command in table.COMMANDS, command
        for verb in verbs or ():
            known = verb in (table.COMMANDS[command].verbs or {})
            assert known or f"{command} {verb}" in table.ELSEWHERE, f"{command} {verb}"
