"""The pure parts of the notebooks' mistake hints: closest names, split values, types, files."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from course_lib.notebook import hints
from course_lib.notebook.value_hints import missing_name_hint

GOLDEN = Path(__file__).resolve().parents[2] / "golden" / "ros2"
CASES = {c["case"]: c for c in json.loads((GOLDEN / "cases.json").read_text())}
VEL_PARAMS = ["start_type_description_service", "use_sim_time", "velocity"]


def _reason(case: str) -> str:
    """Return the reason Jazzy gave in a golden `param set` failure."""
    return CASES[case]["stderr"].removeprefix("Setting parameter failed: ").rstrip("\n")


@pytest.mark.parametrize(
    ("name", "known", "expected"),
    [
        ("velocty", VEL_PARAMS, "velocity"),
        ("Velocity", VEL_PARAMS, "velocity"),
        (
            "/param_vel",
            ["/camera_driver", "/param_vel_node", "/robot_state_publisher"],
            "/param_vel_node",
        ),
        ("/param_vel_nod", ["/param_vel_node", "/param_types_node"], "/param_vel_node"),
        ("speed", VEL_PARAMS, None),
        ("velocity", VEL_PARAMS, None),  # the name itself is no suggestion
        ("x", [], None),
    ],
)
def test_closest_name(name: str, known: list[str], expected: str | None) -> None:
    assert hints.closest(name, known) == expected


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (["param", "set", "/param_types_node", "gains", "[1.0,", "2.0]"], "[1.0, 2.0]"),
        (["param", "set", "/n", "names", "[a,", "b,", "c]", "--no-daemon"], "[a, b, c]"),
        (["param", "set", "--timeout", "3", "/n", "gains", "1.0,", "2.0"], "1.0, 2.0"),
        (["param", "set", "/param_types_node", "gains", "[1.0, 2.0]"], None),  # quoted: fine
        (["param", "set", "/param_vel_node", "velocity", "-1.0"], None),  # a negative number
        (["param", "get", "/n", "gains", "x"], None),
        (["node", "list"], None),
    ],
)
def test_split_value_is_found(argv: list[str], expected: str | None) -> None:
    assert hints.joined_value(argv) == expected


def test_split_hint_quotes_the_whole_value() -> None:
    text = hints.split_hint("[1.0, 2.0]")
    assert "split at its spaces into 2 arguments" in text
    assert "'[1.0, 2.0]'" in text


def test_integer_for_a_double_says_write_1_0() -> None:
    reason = _reason("param_set_int_literal_on_double")
    assert reason == "Wrong parameter type, expected 'Type.DOUBLE' got 'Type.INTEGER'"
    text = hints.type_hint(reason, "velocity", "1")
    assert text is not None and "write `1.0`" in text and "integer" in text


@pytest.mark.parametrize(("value", "meant"), [("abc", "0.2"), ("0,5", "0.5"), ("'0.3'", "0.3")])
def test_text_for_a_double_says_write_a_number(value: str, meant: str) -> None:
    reason = _reason("param_set_wrong_type")
    assert reason.endswith("got 'Type.STRING'")
    text = hints.type_hint(reason, "velocity", value)
    assert text is not None and f"write `{meant}`" in text and "read as text" in text


def test_array_type_says_brackets_and_quotes() -> None:
    reason = "Wrong parameter type, expected 'Type.DOUBLE_ARRAY' got 'Type.DOUBLE'"
    text = hints.type_hint(reason, "gains", "1.0")
    assert text is not None and "'[1.0, 2.0]'" in text and "in quotes" in text


def test_other_reasons_have_no_type_hint() -> None:
    assert hints.type_hint(_reason("param_set_read_only"), "frame_id", "odom") is None


def test_params_files_after_ros_args_only() -> None:
    argv = ["/x/param_vel", "--ros-args", "-r", "__node:=a", "--params-file", "my_files/p.yaml"]
    assert hints.params_files(argv) == ["my_files/p.yaml"]
    assert hints.params_files(["/x/param_vel", "--params-file", "p.yaml"]) == []


@pytest.mark.parametrize(
    ("key", "node", "expected"),
    [
        ("/param_vel_node", "/param_vel_node", True),
        ("param_vel_node", "/param_vel_node", True),
        ("/**", "/param_vel_node", True),
        ("/*", "/param_vel_node", True),
        ("/*", "/ns/param_vel_node", False),
        ("/**/param_vel_node", "/ns/param_vel_node", True),
        ("/some_other_node", "/param_vel_node", False),
        ("/param_vel", "/param_vel_node", False),
    ],
)
def test_key_matches_like_rcl(key: str, node: str, expected: bool) -> None:
    assert hints.key_matches(key, node) is expected


def test_file_sections_of_golden_files() -> None:
    text = (GOLDEN / "params" / "vel_other_node.yaml").read_text()
    assert hints.file_sections(text) == {"/some_other_node": ["velocity"]}
    assert hints.file_sections("[1, 2]") == {}
    assert hints.file_sections("a: [1") == {}  # malformed: ROS itself says so


def test_a_key_naming_no_started_node_is_a_hint() -> None:
    sections = {"/some_other_node": ["velocity"]}
    (text,) = hints.section_hints("p.yaml", sections, {"/param_vel_node": VEL_PARAMS})
    assert "'/some_other_node'" in text and "applied nothing" in text
    assert "'/param_vel_node:'" in text


def test_an_undeclared_parameter_in_a_file_is_a_hint() -> None:
    sections = {"/**": ["velocty"], "/param_vel_node": ["velocity"]}
    (text,) = hints.section_hints("p.yaml", sections, {"/param_vel_node": VEL_PARAMS})
    assert "does not declare 'velocty'" in text and "did you mean 'velocity'?" in text


def test_a_right_file_has_no_hint() -> None:
    sections = {"/param_vel_node": ["velocity"]}
    assert hints.section_hints("p.yaml", sections, {"/param_vel_node": VEL_PARAMS}) == []


def test_started_nodes_counts_a_replaced_node_by_its_log() -> None:
    lines = ["[INFO] [1.5] [param_vel_node]: Velocity parameter is: 0.300000"]
    now = {"/param_vel_node", "/sim"}
    assert hints.started_nodes(lines, {"/param_vel_node", "/sim"}, now) == ["/param_vel_node"]
    assert hints.started_nodes([], {"/sim"}, {"/sim", "/new"}) == ["/new"]


def test_hints_render_apart_as_text_and_html() -> None:
    assert hints.as_text(["write `1.0`."]) == "Hint: write `1.0`.\n"
    html = hints.as_html(["a <b>"])
    assert 'class="course-hint"' in html and "a &lt;b&gt;" in html


def test_disabled_hints_ask_nothing() -> None:
    hints.set_enabled(False)
    try:
        argv = ["param", "set", "/param_vel_node", "velocity", "1"]
        reason = CASES["param_set_int_literal_on_double"]["stderr"]
        assert hints.command_hint(argv, "", reason, lambda: pytest.fail("asked")) is None
    finally:
        hints.set_enabled(True)


def test_a_missing_node_with_none_running_says_start_it() -> None:
    text = missing_name_hint("node", "/param_vel_node", [], "`%ros2 node list`")
    assert text == "no node is running, so there is no '/param_vel_node': start the node first."
    text = missing_name_hint("parameter", "x", [], "`%ros2 param list /n`")
    assert "none with a close name" in text


def test_a_file_value_of_the_wrong_type_is_named() -> None:
    crash = CASES["node_params_file_wrong_type"]["stderr"].splitlines()
    text = hints.crash_hint(crash, ["p.yaml"])
    assert text is not None and text.startswith("in p.yaml: 'velocity' is a double")
    assert "`fast` was read as text" in text
    line = (
        "rclpy.exceptions.InvalidParameterTypeException: Trying to set parameter 'velocity' "
        "to '1' of type 'INTEGER', expecting type 'DOUBLE': velocity"
    )
    assert "write `1.0`" in (hints.crash_hint([line], ["p.yaml"]) or "")
    assert hints.crash_hint([line], []) is None


def test_a_params_file_rcl_cannot_parse_or_open_is_named(tmp_path: Path) -> None:
    crash = CASES["node_params_file_malformed"]["stderr"].splitlines()  # real Jazzy words
    text = hints.crash_hint(crash, ["params/vel_malformed.yaml"], cwd=str(tmp_path))
    assert text is not None and text.startswith(
        "params/vel_malformed.yaml is not a params file ROS can read (rcl stopped reading it "
        "at line 3)"
    )
    missing = (  # the same rclpy error, for a path that names no file (Jazzy, this machine)
        "rclpy._rclpy_pybind11.RCLError: failed to initialize rcl: Couldn't parse params "
        "file: '--params-file my_files/panel.yaml'. Error: Error opening YAML file, at "
        "/project/src/parser.c:271, at /project/src/rcl/arguments.c:415"
    )
    text = hints.crash_hint([missing], ["my_files/panel.yaml"], cwd=str(tmp_path))
    assert text == (
        f"there is no file my_files/panel.yaml in {tmp_path} (a relative path starts in "
        "the folder the node runs in): check its name and folder, for example with "
        "`%ls my_files`."
    )


# --- issue 59: the real cause, in the learner's words ---------------------------------------
SET_OK = "Set parameter successful\n"  # Jazzy's words (golden case param_set_success)


@pytest.mark.parametrize(
    ("value", "way"), [("5.0", "forwards"), ("0.27", "forwards"), ("-0.3", "backwards")]
)
def test_a_velocity_past_top_speed_is_accepted_then_explained(value: str, way: str) -> None:
    words = ["param", "set", "/param_vel_node", "velocity", value]
    assert hints.top_speed_hint(words, SET_OK) == (
        f"/param_vel_node now holds velocity {value} (its velocity has no range), but the "
        f"robot tops out at 0.26 m/s: it drives {way} at 0.26 m/s."
    )


@pytest.mark.parametrize(
    "words",
    [
        ["param", "set", "/param_vel_node", "velocity", "0.26"],
        ["param", "set", "/param_vel_node", "velocity", "-0.2"],
        ["param", "set", "/descriptor_vel_node", "travel_time", "5.0"],
        ["param", "set", "/param_types_node", "max_speed", "1.0"],
    ],
)
def test_a_reachable_velocity_or_another_parameter_has_no_top_speed_hint(
    words: list[str],
) -> None:
    assert hints.top_speed_hint(words, SET_OK) is None


def test_a_successful_set_asks_nothing_of_the_graph() -> None:
    argv = ["param", "set", "/param_vel_node", "velocity", "5.0"]
    text = hints.command_hint(argv, SET_OK, "", lambda: pytest.fail("asked"))
    assert text is not None and "tops out at 0.26 m/s" in text
    argv[-1] = "0.2"
    assert hints.command_hint(argv, SET_OK, "", lambda: pytest.fail("asked")) is None


@pytest.mark.parametrize(
    ("tail", "expected"),
    [
        (["0.15", "m/s"], "`%ros2 param set /param_vel_node velocity 0.15` (velocity is in m/s)."),
        (["0.15", "M/S"], "`%ros2 param set /param_vel_node velocity 0.15` (velocity is in m/s)."),
        (["1", "m/s"], "`%ros2 param set /param_vel_node velocity 1.0` (velocity is in m/s; "
         "the robot tops out at 0.26 m/s)."),
    ],
)  # fmt: skip
def test_a_unit_after_the_value_says_parameters_carry_no_unit(
    tail: list[str], expected: str
) -> None:
    argv = ["param", "set", "/param_vel_node", "velocity", *tail]
    stderr = "usage: ...\nros2: error: unrecognized arguments: m/s\n"
    text = hints.command_hint(argv, "", stderr, lambda: pytest.fail("asked"))
    assert text == "parameters carry no unit: " + expected
    assert "quotes" not in (text or "")


def test_a_unit_on_another_parameter_and_a_split_array() -> None:
    words = ["param", "set", "/descriptor_vel_node", "travel_time", "5", "s"]
    assert hints.unit_hint(words) == (
        "parameters carry no unit: `%ros2 param set /descriptor_vel_node travel_time 5.0` "
        "(travel_time is in s)."
    )
    assert hints.unit_hint(["param", "set", "/n", "gains", "[1.0,", "2.0]"]) is None
    assert hints.unit_hint(["param", "set", "/n", "name", "0.1", "fast"]) is None


@pytest.mark.parametrize("value", ["0.15 m/s", "0.15m/s"])
def test_a_quoted_number_with_a_unit_proposes_the_learners_number(value: str) -> None:
    text = hints.type_hint(_reason("param_set_wrong_type"), "velocity", value)
    assert text == (
        f"'velocity' is a double (a number with a decimal point); `{value}` was read as text "
        "and ROS does not convert it: write `0.15` (parameters carry no unit; velocity is in "
        "m/s)."
    )
    exponent = hints.type_hint(_reason("param_set_wrong_type"), "velocity", "1e-3")
    assert exponent is not None and exponent.endswith("write `0.001`.")  # no unit there


def test_a_number_with_a_unit_for_an_integer_proposes_the_whole_number() -> None:
    reason = "Wrong parameter type, expected 'Type.INTEGER' got 'Type.STRING'"
    assert hints.type_hint(reason, "count", "3 s") == (
        "'count' is an integer; `3 s` was read as text and ROS does not convert it: write `3` "
        "(parameters carry no unit)."
    )


EXECUTABLES = {
    "parameter_tests": ["param_vel"],
    "parameter_descriptors": ["descriptor_vel"],
    "turtlesim": ["turtle_teleop_key", "turtlesim_node"],
}


def _run_hint(stderr: str, argv: list[str]) -> str | None:
    words = hints.run_words(argv)
    assert words is not None
    return hints.run_hint(stderr, words, sorted(EXECUTABLES), lambda p: EXECUTABLES.get(p, []))


def test_a_wrong_executable_names_the_closest_and_the_command() -> None:
    stderr = CASES["run_missing_executable"]["stderr"]  # Jazzy: "No executable found"
    argv = ["run", "parameter_tests", "param_velocity", "--ros-args", "-p", "velocity:=0.1"]
    assert _run_hint(stderr, argv) == (
        "package 'parameter_tests' has no executable 'param_velocity'; did you mean "
        "'param_vel'? `%ros2 run parameter_tests param_vel --ros-args -p velocity:=0.1`."
    )
    assert _run_hint(stderr, ["run", "parameter_tests", "xyz"]) == (
        "package 'parameter_tests' has no executable 'xyz'; its executables are: param_vel "
        "(`%ros2 pkg executables parameter_tests`)."
    )


def test_a_wrong_package_names_the_closest_and_the_command() -> None:
    stderr = CASES["run_missing_package"]["stderr"].replace("no_such_pkg", "parameter_test")
    assert _run_hint(stderr, ["run", "parameter_test", "param_vel"]) == (
        "there is no package 'parameter_test'; did you mean 'parameter_tests'? "
        "`%ros2 run parameter_tests param_vel`."
    )
    assert _run_hint(stderr, ["run", "parameter_test", "param_velo"]) == (
        "there is no package 'parameter_test'; did you mean 'parameter_tests'? It has no "
        "'param_velo' either: did you mean 'param_vel'? `%ros2 run parameter_tests param_vel`."
    )
    far = CASES["run_missing_package"]["stderr"]
    assert _run_hint(far, ["run", "no_such_pkg", "param_vel"]) == (
        "there is no package 'no_such_pkg' and none with a close name; `%ros2 pkg executables` "
        "lists every package's executables."
    )


def test_run_words_skip_the_prefix_option() -> None:
    argv = ["run", "--prefix", "gdb -ex run", "parameter_tests", "param_vel", "--ros-args"]
    assert hints.run_words(argv) == ("parameter_tests", "param_vel", ["--ros-args"])
    assert hints.run_words(["run", "parameter_tests"]) is None
