"""Names the real launch 3.4.3 / launch_ros 0.26.6 modules export (their `__all__`).

Pure data: the shim uses it to tell "the course does not have this" from a typo.
"""

from __future__ import annotations

__all__ = ["REAL_NAMES"]


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
