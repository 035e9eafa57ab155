"""Values typed on the command line are parsed as ros2cli parses them (YAML, no conversion)."""

from __future__ import annotations

import pytest

from course_lib.ros2.values import (
    BOOL,
    BOOL_ARRAY,
    DOUBLE,
    DOUBLE_ARRAY,
    INTEGER,
    INTEGER_ARRAY,
    STRING,
    STRING_ARRAY,
    ParamValue,
    parse_value,
)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("0.2", ParamValue(DOUBLE, 0.2)),
        ("1", ParamValue(INTEGER, 1)),
        ("-1.0", ParamValue(DOUBLE, -1.0)),
        ("true", ParamValue(BOOL, True)),
        ("abc", ParamValue(STRING, "abc")),
        ("1e3", ParamValue(STRING, "1e3")),
        ("", ParamValue(STRING, "")),
        ("~", ParamValue(STRING, "~")),
        ("[1.0, 2.0]", ParamValue(DOUBLE_ARRAY, (1.0, 2.0))),
        ("[1, 2]", ParamValue(INTEGER_ARRAY, (1, 2))),
        ("[true, false]", ParamValue(BOOL_ARRAY, (True, False))),
        ("[a, b]", ParamValue(STRING_ARRAY, ("a", "b"))),
        ("[1, 2.0]", ParamValue(STRING, "[1, 2.0]")),
        ("[1.0, 2", ParamValue(STRING, "[1.0, 2")),
        ("[]", ParamValue(BOOL_ARRAY, ())),
    ],
)
def test_parse_value_follows_yaml_rules(text: str, expected: ParamValue) -> None:
    assert parse_value(text) == expected


def test_python_values_map_to_ros_types() -> None:
    assert ParamValue.of(0.2).type_name == "double"
    assert ParamValue.of(1).type_name == "integer"
    assert ParamValue.of([True]).type_name == "boolean array"
    assert ParamValue.of(["a"]).python == ["a"]
    with pytest.raises(TypeError):
        ParamValue.of([1, "a"])


def test_parse_value_is_rclpys_guess_and_refuses_a_mapping_in_its_words() -> None:
    from rclpy.parameter import get_parameter_value

    for text in ("0.2", "[1, 2]", "[a, b]", "[1, 2.0]", "~", "1e3"):
        msg = get_parameter_value(text)
        assert parse_value(text).type == msg.type, text
    with pytest.raises(AssertionError, match=r"^The 'string_value' field must be of type 'str'$"):
        parse_value("{a: 1}")
