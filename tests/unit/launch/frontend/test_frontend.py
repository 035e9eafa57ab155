"""XML/YAML launch files and the `$(...)` language, evaluated without running anything."""

from __future__ import annotations

from pathlib import Path

import pytest

from course_lib.launch.api.substitution_syntax import parse_substitution
from course_lib.launch.api.substitutions import perform_substitutions
from course_lib.launch.core.context import LaunchContext
from course_lib.launch.core.description import load_any_launch_file

FIXTURE = Path(__file__).resolve().parents[3] / "fixtures" / "launch_pkg"


def _eval(text: str, **configs: str) -> str:
    context = LaunchContext()
    context.launch_configurations.update(configs)
    return perform_substitutions(context, parse_substitution(text))


def test_var_and_text_mix() -> None:
    assert _eval("a $(var x) b", x="1") == "a 1 b"


def test_var_default_quoted_with_nested_substitution() -> None:
    assert _eval("$(var missing '$(var x)/c')", x="/p") == "/p/c"


def test_unknown_substitution_is_named() -> None:
    with pytest.raises(RuntimeError, match="Unknown substitution: nope"):
        parse_substitution("$(nope a)")


def test_missing_configuration_message() -> None:
    with pytest.raises(RuntimeError, match="launch configuration 'x' does not exist"):
        _eval("$(var x)")


def _nodes(path: Path, **configs: str) -> list:
    context = LaunchContext()
    context.launch_configurations.update(configs)
    pending = [load_any_launch_file(str(path))]
    while pending:
        entity = pending.pop(0)
        context.push_locals()
        pending = list(entity.visit(context) or []) + pending
    return context.planned_processes


def test_yaml_node_parameters(ament_fixture: Path) -> None:
    (node,) = _nodes(FIXTURE / "launch" / "param_vel.launch.yaml")
    assert node.spec.name == "param_vel-1"
    assert node.node_name == "<node_namespace_unspecified>/param_vel_node"
    assert node.parameter_sources[0].values == {"velocity": 0.2}
    assert node.spec.output == "screen" and not node.spec.emulate_tty


def test_xml_param_value_is_typed_like_launch_xml(ament_fixture: Path) -> None:
    (node,) = _nodes(FIXTURE / "launch" / "param_vel.launch.xml", velocity="1")
    assert node.parameter_sources[0].values == {"velocity": 1}  # an integer, as real XML gives


def test_unknown_xml_tag_is_reported(tmp_path: Path) -> None:
    path = tmp_path / "bad.launch.xml"
    path.write_text("<launch><nod pkg='a' exec='b'/></launch>")
    with pytest.raises(Exception, match="RuntimeError: Unrecognized entity of the type: nod"):
        load_any_launch_file(str(path))


def test_tags_and_substitutions_the_course_lacks_fail_in_one_line(tmp_path: Path) -> None:
    from course_lib.launch.core.loading import CourseUnavailableError

    container = tmp_path / "container.launch.xml"
    container.write_text(
        '<launch><node_container pkg="rclcpp_components" exec="component_container" '
        'name="c" namespace=""/></launch>'
    )
    with pytest.raises(CourseUnavailableError) as tag:
        load_any_launch_file(str(container))
    assert str(tag.value).startswith(
        "'node_container' (a launch file tag) is not available in this course; it has: arg, "
    )
    anon = tmp_path / "anon.launch.yaml"
    anon.write_text("launch:\n- log:\n    message: $(anon talker)\n")
    with pytest.raises(CourseUnavailableError, match=r"^'\$\(anon \.\.\.\)' is not available"):
        load_any_launch_file(str(anon))
    typo = tmp_path / "typo.launch.xml"
    typo.write_text("<launch><nodee/></launch>")
    with pytest.raises(Exception, match="Unrecognized entity of the type: nodee"):
        load_any_launch_file(str(typo))


def test_a_dry_run_says_which_code_reading_the_file_ran(tmp_path: Path) -> None:
    """$(eval) and $(command) run code while the file is read, as upstream: the dry run says so."""
    from course_lib.launch.command.dry_run import dry_run_file

    path = tmp_path / "code.launch.xml"
    path.write_text(
        '<launch>\n  <let name="a" value="$(eval \'2 * 21\')"/>\n'
        '  <let name="b" value="$(command \'echo hi\')"/>\n</launch>\n'
    )
    warnings = dry_run_file(str(path), []).warnings
    assert [w.split(" (as")[0] for w in warnings] == [
        "reading this launch file ran a Python expression: 2 * 21",
        "reading this launch file ran a command: echo hi",
    ]
    plain = tmp_path / "plain.launch.xml"
    plain.write_text('<launch>\n  <let name="a" value="42"/>\n</launch>\n')
    assert dry_run_file(str(plain), []).warnings == []


def test_a_yaml_launch_file_of_nested_aliases_is_refused_at_once_naming_it(
    tmp_path: Path,
) -> None:
    import time

    from course_lib.launch.core.loading import InvalidLaunchFileError

    lines = ["launch:", "- arg: &l0 {name: x, default: '1'}"]  # 2 KB that expand to 2**26
    lines += [f"- let: &l{n} {{name: l{n}, value: [*l{n - 1}, *l{n - 1}]}}" for n in range(1, 27)]
    path = tmp_path / "bomb.launch.yaml"
    path.write_text("\n".join(lines) + "\n")
    started = time.monotonic()
    with pytest.raises(InvalidLaunchFileError) as refused:
        load_any_launch_file(str(path))
    assert time.monotonic() - started < 2.0
    assert f"{path}, line " in str(refused.value) and "aliases" in str(refused.value)
