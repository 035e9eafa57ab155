"""The skill exercises' words: each mistake's verdict and its hints, from general to specific
(attempt 1, 2, 3 and later), with the learner's own numbers filled in by `judge` (pure)."""

from __future__ import annotations

__all__ = ["HINTS", "MESSAGES"]

# kind -> hints, from general to specific (attempt 1, 2, 3 and later)
HINTS: dict[str, tuple[str, str, str]] = {
    "no_motion": (
        "is velocity set on the node that drives the robot? `%ros2 param get {node} velocity`",
        "did `param set` answer 'Set parameter successful'? {refused_text}",
        "velocity = distance ÷ time = {distance_m:g} ÷ {time_s:g}, written as a double, set on "
        "{node} before you run the check.",
    ),
    "wrong_node": (
        "which node drives the robot? `%ros2 topic info /cmd_vel --verbose` names the publisher.",
        "{elsewhere} holds velocity {elsewhere_value:g}, but the robot follows {node}.",
        "set the same value on {node}: `%ros2 param set {node} velocity <value>`.",
    ),
    "over_top_speed": (
        "velocity is a speed in m/s: the one that drives {distance_m:g} m in {time_s:g} s is "
        "below the robot's top speed, {top} m/s.",
        "at velocity v the robot drives v × {time_s:g} m in the check's {time_s:g} s, so "
        "v × {time_s:g} = {distance_m:g}.",
        "velocity = {distance_m:g} ÷ {time_s:g} (m/s), set as a double on {node}.",
    ),
    "too_short": (
        "distance = velocity × time: the check measures {time_s:g} s of simulated time.",
        "it drove {measured_m:.2f} m in {time_s:g} s, so at {measured_mps:.2f} m/s; "
        "{distance_m:g} m in the same time needs a higher velocity.",
        "velocity = {distance_m:g} ÷ {time_s:g} (m/s), set as a double on {node}.",
    ),
    "too_far": (
        "distance = velocity × time: the check measures {time_s:g} s of simulated time.",
        "it drove {measured_m:.2f} m in {time_s:g} s, so at {measured_mps:.2f} m/s; "
        "{distance_m:g} m in the same time needs a lower velocity.",
        "velocity = {distance_m:g} ÷ {time_s:g} (m/s), set as a double on {node}.",
    ),
    "not_started": (
        "the check judges the node you start after arming it: start {node} again.",
        "stop the running node first, then start it with the file that holds the new value.",
        "{how}",
    ),
    "integer": (
        "the node stopped at start-up: read its last line (InvalidParameterTypeException).",
        "`{param}` is declared as a double; `{written}` is read as an integer, and ROS does not "
        "convert it.",
        "write the value with a decimal point, `{target:.2f}`, in {source}.",
    ),
    "missing_file": (
        "the node's last line says why it ended: rcl could not open the params file.",
        "a relative path after `--params-file` starts in the folder the node runs in (the "
        "notebook's): check the file's name and folder, for example with `%ls my_files`.",
        "{how}",
    ),
    "unreadable": (
        "the node's last line says why it ended: rcl could not parse the params file (it "
        "names the line).",
        "look at {source} with `lesson.show_file(...)`: a bracket or quote left open, a tab, "
        "or a line indented differently from its neighbours.",
        "the file holds `{node}:`, under it `  ros__parameters:`, under that "
        "`    {param}: {target:.2f}`.",
    ),
    "no_file": (
        "the value must be there from the node's first second: give it to the node at start-up.",
        "`ros2 run` takes a params file after `--ros-args`: `--params-file <file>`.",
        "{how}",
    ),
    "wrong_key": (
        "the node started with {param} {first:g}: ROS applied nothing from {source}, and "
        "says nothing about it.",
        "the file's top key `{key}` names no node that runs; ROS applies a section only to the "
        "node it names.",
        "make the top key `{node}:` (or `/**:` for every node).",
    ),
    "undeclared": (
        "rename `{key}` to `{param}` in {source}: ROS gives a node only the parameters it "
        "declares, and {node} declares `{param}`.",
        "`%ros2 param list {node}` lists the names {node} declares: every name under "
        "`ros__parameters:` in {source} must be one of them, spelt the same.",
        "make the line `{key}: {written}` in {source} read `{param}: {written}`, then start "
        "the node again.",
    ),
    "nested": (
        "in {source}, `{param}` must sit directly under `ros__parameters:`: a key between "
        "them makes another, dotted name.",
        "`%ros2 param list {node}` shows the names {node} declares: `{param}`, not `{key}`.",
        "in {source}, delete the line that opens the level above `{param}: {written}` and "
        "indent that line one level less, then start the node again.",
    ),
    "file_sets_none": (
        "ROS gives {node} only what `ros__parameters:` under `{key}:` in {source} sets: add "
        "`{param}` there.",
        "`%ros2 param dump {node}` prints every parameter {node} has, laid out as {source} "
        "needs them.",
        "under `ros__parameters:` in {source}, add the line `{param}: {target:.2f}` (indented "
        "like its neighbours), then start the node again.",
    ),
    "no_ros_parameters": (
        "ROS reads a node's parameters only under `ros__parameters:`: in {source}, add that "
        "line under `{key}:` and indent `{written}` under it.",
        "rcl says the same on the node's last line: 'Cannot have a value before ros__parameters'.",
        "the file holds `{node}:`, under it `  ros__parameters:`, under that "
        "`    {param}: {target:.2f}`.",
    ),
    "empty_section": (
        "a params file has three levels: the node's name, under it `ros__parameters:`, under "
        "that the parameters; {source} stops after `{key}:`.",
        "rcl says so on the node's last line ('Cannot have a value before ros__parameters'): "
        "fill in the levels under `{key}:`.",
        "the file holds `{node}:`, under it `  ros__parameters:`, under that "
        "`    {param}: {target:.2f}`.",
    ),
    "no_node_key": (
        "put `{node}:` (or `/**:`) on the first line of {source} and indent the rest under it: "
        "ROS applies a section only to the node it names.",
        "rcl says so on the node's last line: 'There are no node names before ros__parameters'.",
        "the file holds `{node}:`, under it `  ros__parameters:`, under that "
        "`    {param}: {target:.2f}`.",
    ),
    "no_parameter": (
        "the node started with velocity {first:g}: the launch file gave it no velocity.",
        "a Node action takes its values as `parameters=[{{'name': value}}]`.",
        "add `parameters=[{{'velocity': {target:.2f}}}]` to the Node of {source}.",
    ),
    "after_window": (
        "{measured_text} only after the node's first seconds: the value came later.",
        "the node started with {param} {first:g}; a value set after the start is not the "
        "start-up value. Put it in {source} before the start.",
        "{how}",
    ),
    "wrong_value": (
        "{measured_text}; the task wants {param} {target:g}.",
        "look at the value {source} gives: `lesson.show_file(...)`.",
        "write `{param}: {target:g}` (a double) in {source}, then start the node again.",
    ),
}

MESSAGES = {
    "no_motion": "the robot did not move.",
    "wrong_node": "the robot did not drive the distance.",
    "over_top_speed": "the robot drove {measured_m:.2f} m in {time_s:g} s, not {distance_m:g} m "
    "(± {tolerance_cm:g} cm): {node} holds velocity {velocity:g}, but the robot tops out at "
    "{top} m/s, forwards or backwards, and drove at that. The answer's velocity is "
    "distance ÷ time.",
    "too_short": "the robot drove {measured_m:.2f} m in {time_s:g} s, short of {distance_m:g} m "
    "(± {tolerance_cm:g} cm).",
    "too_far": "the robot drove {measured_m:.2f} m in {time_s:g} s, past {distance_m:g} m "
    "(± {tolerance_cm:g} cm).",
    "not_started": "no {executable} was started by this lesson since the exercise was armed.",
    "integer": "{node} did not start: its {param} is an integer.",
    "missing_file": "{node} did not start: there is no file {source}.",
    "unreadable": "{node} did not start: ROS cannot read {source}.",
    "no_file": "{node} started without a params file.",
    "wrong_key": "{node} started with {param} {first:g}: the params file did not reach it.",
    "undeclared": "{source} sets `{key}: {written}`, which {node} does not declare: ROS keeps "
    "it silently as an undeclared override, so {node} started with {param} {first:g}.",
    "nested": "{source} sets `{param}` one level too deep, as `{key}`, which {node} does not "
    "declare: ROS keeps it silently, so {node} started with {param} {first:g}.",
    "file_sets_none": "{node} started with {param} {first:g}: {source} sets no `{param}` under "
    "`{key}: ros__parameters:`.",
    "no_ros_parameters": "{node} did not start: in {source}, `{written}` sits right under "
    "`{key}:`, with no `ros__parameters:` between them.",
    "empty_section": "{node} did not start: `{key}:` in {source} has nothing under it, and rcl "
    "cannot read that.",
    "no_node_key": "{node} did not start: {source} begins with `ros__parameters:`, with no "
    "node's name above it.",
    "no_parameter": "{node} started with {param} {first:g}: the launch file sets none.",
    "after_window": "{node} started with {param} {first:g}, and got {target:g} only later.",
    "wrong_value": "{measured_text}, not {target:g} {unit} (± {tolerance:g}).",
}
