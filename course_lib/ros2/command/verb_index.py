"""The `ros2` commands and verbs of course_lib/ros2/verbs (generated: do not edit).

Written from the declarations beside each verb (course_lib/ros2/verbkit/registry.py) by
`python -m course_lib.ros2.command.index_builder`, so that a terminal's `ros2` knows every
verb without importing it; tests/unit/ros2/command/test_verb_registry.py fails while the
two differ.
"""

# name: (help line, options builder before its verb, raw handler)
COMMANDS = {
    "daemon": (
        "Various daemon related sub-commands",
        None,
        None,
    ),
    "interface": (
        "Show information about ROS interfaces",
        None,
        None,
    ),
    "launch": (
        "Run a launch file",
        None,
        "verbs.launch:main",
    ),
    "node": (
        "Various node related sub-commands",
        None,
        None,
    ),
    "param": (
        "Various param related sub-commands",
        None,
        None,
    ),
    "pkg": (
        "Various package related sub-commands",
        None,
        None,
    ),
    "run": (
        "Run a package specific executable",
        None,
        None,
    ),
    "service": (
        "Various service related sub-commands",
        "verbs.service:command_arguments",
        None,
    ),
    "topic": (
        "Various topic related sub-commands",
        "verbs.topic:topic_command_arguments",
        None,
    ),
}
# (command, verb): (help line, handler, arguments builder, uses the ROS graph);
# verb "": the command is itself the verb (`ros2 run`)
VERBS = {
    ("daemon", "start"): (
        "Start the daemon if it isn't running",
        "verbs.daemon:daemon_start",
        "verbs.daemon:daemon_start_arguments",
        False,
    ),
    ("daemon", "status"): (
        "Output the status of the daemon",
        "verbs.daemon:daemon_status",
        None,
        False,
    ),
    ("daemon", "stop"): (
        "Stop the daemon if it is running",
        "verbs.daemon:daemon_stop",
        None,
        False,
    ),
    ("interface", "list"): (
        "List all interface types available",
        "verbs.interface:list_",
        "verbs.interface:list_arguments",
        False,
    ),
    ("interface", "package"): (
        "Output a list of available interface types within one package",
        "verbs.interface:package",
        "verbs.interface:package_arguments",
        False,
    ),
    ("interface", "packages"): (
        "Output a list of packages that provide interfaces",
        "verbs.interface:packages",
        "verbs.interface:packages_arguments",
        False,
    ),
    ("interface", "proto"): (
        "Output an interface prototype",
        "verbs.interface:proto",
        "verbs.interface:proto_arguments",
        False,
    ),
    ("interface", "show"): (
        "Output the interface definition",
        "verbs.interface:show",
        "verbs.interface:show_arguments",
        False,
    ),
    ("node", "info"): (
        "Output information about a node",
        "verbs.node:node_info",
        "verbs.node:node_info_arguments",
        True,
    ),
    ("node", "list"): (
        "Output a list of available nodes",
        "verbs.node:node_list",
        "verbs.node:node_list_arguments",
        True,
    ),
    ("param", "delete"): (
        "Delete parameter",
        "verbs.param:param_delete",
        "verbs.param:param_delete_arguments",
        True,
    ),
    ("param", "describe"): (
        "Show descriptive information about declared parameters",
        "verbs.param:param_describe",
        "verbs.param:param_describe_arguments",
        True,
    ),
    ("param", "dump"): (
        "Show all of the parameters of a node in a YAML file format",
        "verbs.param:param_dump",
        "verbs.param:param_dump_arguments",
        True,
    ),
    ("param", "get"): (
        "Get parameter",
        "verbs.param:param_get",
        "verbs.param:param_get_arguments",
        True,
    ),
    ("param", "list"): (
        "Output a list of available parameters",
        "verbs.param:param_list",
        "verbs.param:param_list_arguments",
        True,
    ),
    ("param", "load"): (
        "Load parameter file for a node",
        "verbs.param:param_load",
        "verbs.param:param_load_arguments",
        True,
    ),
    ("param", "set"): (
        "Set parameter",
        "verbs.param:param_set",
        "verbs.param:param_set_arguments",
        True,
    ),
    ("pkg", "create"): (
        "Create a new ROS 2 package",
        "verbs.pkg.create:main",
        "verbs.pkg.create:add_arguments",
        False,
    ),
    ("pkg", "executables"): (
        "Output a list of package specific executables",
        "verbs.pkg.executables:pkg_executables",
        "verbs.pkg.executables:pkg_executables_arguments",
        False,
    ),
    ("pkg", "prefix"): (
        "Output the prefix path of a package",
        "verbs.pkg.executables:pkg_prefix",
        "verbs.pkg.executables:pkg_prefix_arguments",
        False,
    ),
    ("run", ""): (
        "Run a package specific executable",
        "verbs.pkg.executables:run",
        "verbs.pkg.executables:run_arguments",
        False,
    ),
    ("service", "call"): (
        "Call a service",
        "verbs.service_call:main",
        "verbs.service_call:add_arguments",
        True,
    ),
    ("service", "find"): (
        "Output a list of available services of a given type",
        "verbs.service:find",
        "verbs.service:find_arguments",
        True,
    ),
    ("service", "info"): (
        "Print information about a service",
        "verbs.service:info",
        "verbs.service:info_arguments",
        True,
    ),
    ("service", "list"): (
        "Output a list of available services",
        "verbs.service:list_",
        "verbs.service:list_arguments",
        True,
    ),
    ("service", "type"): (
        "Output a service's type",
        "verbs.service:type_",
        "verbs.service:type_arguments",
        True,
    ),
    ("topic", "bw"): (
        "Display bandwidth used by topic",
        "verbs.topic:bw",
        "verbs.topic:bw_arguments",
        True,
    ),
    ("topic", "delay"): (
        "Display delay of topic from timestamp in header",
        "verbs.topic:delay",
        "verbs.topic:delay_arguments",
        True,
    ),
    ("topic", "echo"): (
        "Output messages from a topic",
        "verbs.topic_stream:topic_echo",
        "verbs.topic_stream:topic_echo_arguments",
        True,
    ),
    ("topic", "find"): (
        "Output a list of available topics of a given type",
        "verbs.topic:find",
        "verbs.topic:find_arguments",
        True,
    ),
    ("topic", "hz"): (
        "Print the average publishing rate to screen",
        "verbs.topic_stream:topic_hz",
        "verbs.topic_stream:topic_hz_arguments",
        True,
    ),
    ("topic", "info"): (
        "Print information about a topic",
        "verbs.topic:info",
        "verbs.topic:info_arguments",
        True,
    ),
    ("topic", "list"): (
        "Output a list of available topics",
        "verbs.topic:topic_list",
        "verbs.topic:topic_list_arguments",
        True,
    ),
    ("topic", "pub"): (
        "Publish a message to a topic",
        "verbs.topic_pub:main",
        "verbs.topic_pub:add_arguments",
        True,
    ),
    ("topic", "type"): (
        "Print a topic's type",
        "verbs.topic:type_",
        "verbs.topic:type_arguments",
        True,
    ),
}
