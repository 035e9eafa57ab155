"""Names the real launch 3.4.3 / launch_ros 0.26.6 modules export (their `__all__`).

Pure data: the shim uses it to tell "the course does not have this" from a typo.
"""

from __future__ import annotations

__all__ = ["REAL_FRONTEND_SUBSTITUTIONS", "REAL_FRONTEND_TAGS", "REAL_NAMES"]


def _names(text: str) -> tuple[str, ...]:
    return tuple(text.split())


REAL_NAMES: dict[str, tuple[str, ...]] = {
    "launch": _names(
        "Action Condition Event EventHandler InvalidLaunchFileError LaunchContext "
        "LaunchDescription LaunchDescriptionEntity LaunchDescriptionSource LaunchIntrospector "
        "LaunchService SomeEntitiesType SomeEntitiesType_types_tuple SomeSubstitutionsType "
        "SomeSubstitutionsType_types_tuple Substitution actions conditions descriptions events "
        "frontend logging substitutions"
    ),
    "launch.actions": _names(
        "AppendEnvironmentVariable DeclareLaunchArgument EmitEvent ExecuteLocal ExecuteProcess "
        "GroupAction IncludeLaunchDescription LogInfo OpaqueCoroutine OpaqueFunction "
        "PopEnvironment PopLaunchConfigurations PushEnvironment PushLaunchConfigurations "
        "ResetEnvironment ResetLaunchConfigurations RegisterEventHandler SetEnvironmentVariable "
        "SetLaunchConfiguration Shutdown TimerAction UnregisterEventHandler "
        "UnsetEnvironmentVariable UnsetLaunchConfiguration"
    ),
    "launch.substitutions": _names(
        "AllSubstitution AndSubstitution AnySubstitution AnonName Command EqualsSubstitution "
        "EnvironmentVariable FileContent FindExecutable IfElseSubstitution LaunchConfiguration "
        "LaunchLogDir LocalSubstitution NotSubstitution NotEqualsSubstitution OrSubstitution "
        "PathJoinSubstitution PythonExpression SubstitutionFailure TextSubstitution "
        "ThisLaunchFile ThisLaunchFileDir"
    ),
    "launch.conditions": _names(
        "evaluate_condition_expression IfCondition InvalidConditionExpressionError "
        "LaunchConfigurationEquals LaunchConfigurationNotEquals UnlessCondition"
    ),
    "launch.event_handlers": _names(
        "event_named OnExecutionComplete OnIncludeLaunchDescription OnProcessExit OnProcessIO "
        "OnProcessStart OnShutdown"
    ),
    "launch.events": _names(
        "matches_action process ExecutionComplete IncludeLaunchDescription Shutdown TimerEvent"
    ),
    "launch.events.process": _names(
        "matches_executable matches_name matches_pid ProcessExited ProcessIO ProcessStarted "
        "ProcessStderr ProcessStdin ProcessStdout ProcessTargetedEvent RunningProcessEvent "
        "ShutdownProcess SignalProcess"
    ),
    "launch.launch_description_sources": _names(
        "get_launch_description_from_any_launch_file "
        "get_launch_description_from_python_launch_file "
        "get_launch_description_from_frontend_launch_file InvalidFrontendLaunchFileError "
        "InvalidLaunchFileError InvalidPythonLaunchFileError load_python_launch_file_as_module "
        "AnyLaunchDescriptionSource FrontendLaunchDescriptionSource "
        "PythonLaunchDescriptionSource"
    ),
    "launch_ros": _names("actions descriptions event_handlers events ros_adapters substitutions"),
    "launch_ros.actions": _names(
        "ComposableNodeContainer LifecycleNode LifecycleTransition LoadComposableNodes Node "
        "PushROSNamespace PushRosNamespace ROSTimer RosTimer SetParameter SetParametersFromFile "
        "SetRemap SetROSLogDir SetUseSimTime"
    ),
    "launch_ros.substitutions": _names(
        "ExecutableInPackage FindPackage FindPackagePrefix FindPackageShare Parameter"
    ),
    "launch_ros.descriptions": _names("ComposableNode Parameter ParameterFile ParameterValue"),
    "launch_ros.event_handlers": ("OnStateTransition",),
    "launch_ros.events": ("lifecycle", "matches_node_name"),
}

# Tags and `$(...)` substitutions of XML/YAML launch files (`expose_action`/`expose_substitution`).
REAL_FRONTEND_TAGS = _names(
    "append_env arg executable group include let log reset reset_env set_env shutdown timer "
    "unset_env load_composable_node node node_container push-ros-namespace push_ros_namespace "
    "ros_timer set_parameter set_parameters_from_file set_remap set_ros_log_dir set_use_sim_time"
)
REAL_FRONTEND_SUBSTITUTIONS = _names(
    "all and anon any command dirname env equals eval file-content filename find-exec if "
    "launch_log_dir log_dir not not-equals or var exec-in-pkg find-pkg-prefix find-pkg-share param"
)
