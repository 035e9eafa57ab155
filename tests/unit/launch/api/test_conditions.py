"""Conditions and event handlers: what decides whether, and when, an action runs."""

from __future__ import annotations

import sys

import pytest

from course_lib.launch.api.actions import LogInfo
from course_lib.launch.api.conditions import (
    IfCondition,
    InvalidConditionExpressionError,
    LaunchConfigurationEquals,
    LaunchConfigurationNotEquals,
    UnlessCondition,
)
from course_lib.launch.api.process import ExecuteProcess
from course_lib.launch.api.substitutions import LaunchConfiguration, PythonExpression
from course_lib.launch.core.context import LaunchContext
from course_lib.launch.core.event_handlers import OnExecutionComplete, OnProcessExit, OnShutdown
from course_lib.launch.core.events import ExecutionComplete, ProcessExited, Shutdown
from course_lib.launch.runtime.shim import launch_modules


def _context(**configs: str) -> LaunchContext:
    context = LaunchContext()
    context.launch_configurations.update(configs)
    return context


@pytest.mark.parametrize(
    "text,expected",
    [("true", True), (" True ", True), ("1", True), ("false", False), ("0", False)],
)
def test_if_and_unless_read_true_and_false(text: str, expected: bool) -> None:
    assert IfCondition(text).evaluate(_context()) is expected
    assert UnlessCondition(text).evaluate(_context()) is not expected


def test_if_condition_with_python_expression() -> None:
    context = _context(v="200", red="True")
    expression = PythonExpression(
        [LaunchConfiguration("v"), " == 200 and ", LaunchConfiguration("red")]
    )
    assert IfCondition(expression).evaluate(context) is True
    context.launch_configurations["red"] = "False"
    assert IfCondition(expression).evaluate(context) is False


def test_invalid_condition_text_is_launchs_message() -> None:
    with pytest.raises(InvalidConditionExpressionError) as caught:
        IfCondition(["ye", LaunchConfiguration("s")]).evaluate(_context(s="s"))
    assert str(caught.value) == (
        "invalid condition expression, expected one of [true, 1, false, 0] but got 'yes', "
        "expanded from ''ye' + LaunchConfig('s')'"
    )


def test_launch_configuration_equals_and_not_equals() -> None:
    with pytest.warns(UserWarning, match="'LaunchConfigurationEquals' and"):
        equals = LaunchConfigurationEquals("mode", "fast")
    with pytest.warns(UserWarning):
        unset = LaunchConfigurationEquals("mode", None)
    with pytest.warns(UserWarning):
        not_equals = LaunchConfigurationNotEquals("mode", "fast")
    assert equals.evaluate(_context(mode="fast")) is True
    assert equals.evaluate(_context(mode="slow")) is False
    assert not_equals.evaluate(_context(mode="slow")) is True
    assert unset.evaluate(_context()) is True
    assert unset.evaluate(_context(mode="x")) is False


def _process_event(cls: type, action: object, **extra: object) -> object:
    return cls(action=action, name="p-1", cmd=["p"], cwd=None, env=None, pid=1, **extra)


def test_process_handlers_match_their_target_only() -> None:
    target, other = ExecuteProcess(cmd=["true"]), ExecuteProcess(cmd=["true"])
    log = LogInfo(msg="exited")
    handler = OnProcessExit(target_action=target, on_exit=[log])
    assert handler.matches(_process_event(ProcessExited, target, returncode=0))
    assert not handler.matches(_process_event(ProcessExited, other, returncode=0))
    assert not handler.matches(ExecutionComplete(action=target))
    context = _context()
    event = _process_event(ProcessExited, target, returncode=0)
    assert handler.handle(event, context) == [log]
    assert context.locals.event is event


def test_handlers_reject_non_entities_and_call_functions() -> None:
    with pytest.raises(TypeError, match="'on_completion' iterable"):
        OnExecutionComplete(on_completion=["not an action"])
    seen: list[str] = []
    handler = OnShutdown(on_shutdown=lambda event, _context: seen.append(event.reason))
    handler.handle(Shutdown(reason="idle"), _context())
    assert seen == ["idle"]


def test_newest_handler_first_and_execution_complete_only_when_handled() -> None:
    context = _context()
    first, second = OnShutdown(on_shutdown=[]), OnShutdown(on_shutdown=[])
    context.register_event_handler(first)
    context.register_event_handler(second)
    assert list(context.event_handlers) == [second, first]
    log = LogInfo(msg="x")
    log.visit(context)
    assert not context.event_queue  # nobody listens for ExecutionComplete
    context.register_event_handler(OnExecutionComplete(target_action=log, on_completion=[]))
    log.visit(context)
    assert [type(e) for e in context.event_queue] == [ExecutionComplete]


def test_shim_names_what_the_course_lacks_and_suggests_typos() -> None:
    with launch_modules():
        with pytest.raises(ImportError) as lacking:
            from launch_ros.actions import LifecycleNode  # type: ignore[import-not-found] # noqa: F401
        with pytest.raises(ImportError) as typo:
            from launch.actions import RegisterEventHandlr  # type: ignore[import-not-found] # noqa: F401
        with pytest.raises(ImportError) as wrong_package:
            from launch.substitutions import FindPackageShare  # type: ignore[import-not-found] # noqa: F401
        with pytest.raises(ImportError) as module:
            import launch.frontend  # type: ignore[import-not-found] # noqa: F401
        from launch.event_handlers import OnProcessIO  # type: ignore[import-not-found]
    assert OnProcessIO.__module__ == "course_lib.launch.core.event_handlers"
    assert str(lacking.value).startswith(
        "'LifecycleNode' of 'launch_ros.actions' is not available in this course; "
        "'launch_ros.actions' here has: Node, "
    )
    assert str(typo.value) == (
        "cannot import name 'RegisterEventHandlr' from 'launch.actions' (unknown location). "
        "Did you mean: 'RegisterEventHandler'?"
    )
    assert str(wrong_package.value) == (
        "cannot import name 'FindPackageShare' from 'launch.substitutions' (unknown location). "
        "It is in 'launch_ros.substitutions'"
    )
    assert str(module.value) == "module 'launch.frontend' is not available in this course"
    assert "launch" not in sys.modules and "launch.frontend" not in sys.modules


def test_show_args_marks_arguments_that_depend_on_a_condition_or_event() -> None:
    from course_lib.launch.api.event_actions import RegisterEventHandler
    from course_lib.launch.command.describe import format_arguments
    from course_lib.launch.core.description import LaunchDescription
    from course_lib.launch.core.launch_argument import DeclareLaunchArgument

    description = LaunchDescription(
        [
            DeclareLaunchArgument("plain", default_value="a"),
            DeclareLaunchArgument("maybe", default_value="b", condition=IfCondition("true")),
            RegisterEventHandler(
                OnProcessExit(on_exit=[DeclareLaunchArgument("late", default_value="c")])
            ),
        ]
    )
    text = format_arguments(description)
    assert "'plain':\n" in text
    assert "'maybe':*\n" in text and "'late':*\n" in text
    assert text.endswith("\n* argument(s) which are only used if specific conditions occur\n")


def _visit_all(entity: object, context: LaunchContext) -> None:
    for sub in entity.visit(context) or []:  # type: ignore[attr-defined]
        _visit_all(sub, context)


def test_group_scopes_and_forwarding() -> None:
    from course_lib.launch.api.actions import GroupAction, SetLaunchConfiguration

    context = _context(outer="1")
    seen: dict[str, dict[str, str]] = {}

    def record(name: str) -> object:
        from course_lib.launch.api.actions import OpaqueFunction

        return OpaqueFunction(
            function=lambda ctx: seen.__setitem__(name, dict(ctx.launch_configurations))
        )

    _visit_all(GroupAction([SetLaunchConfiguration("inner", "2"), record("scoped")]), context)
    _visit_all(
        GroupAction([record("fresh")], forwarding=False, launch_configurations={"k": "v"}),
        context,
    )
    _visit_all(GroupAction([SetLaunchConfiguration("leak", "3")], scoped=False), context)
    assert seen == {"scoped": {"outer": "1", "inner": "2"}, "fresh": {"k": "v"}}
    assert context.launch_configurations == {"outer": "1", "leak": "3"}
