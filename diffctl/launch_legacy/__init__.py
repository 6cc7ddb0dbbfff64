"""The launch engine: descriptions (YAML, XML and Python), resolution, and leak-proof process supervision.

Python launch files use these names, as in ROS 2's `launch` / `launch_ros`:

    from diffctl.launch_legacy import LaunchDescription, Node, RegisterEventHandler, OnProcessExit

The engine knows processes, not robots: it imports nothing of diffctl but errors and console.
The names are imported on first use (PEP 562): the fork server (`python -m diffctl.launch_legacy.zygote`) and the
forked components import this package but none of the engine, which costs 0.2-0.3 s to import.
"""

from __future__ import annotations

import importlib

# Every public name and the module it lives in: the one list (`__all__` is derived from it).
_ORIGIN: dict[str, str] = {
    "FindPackage": "diffctl.launch_legacy.ros_substitutions",
    "LifecycleTransition": "diffctl.launch_legacy.lifecycle_transition",
    "OnIncludeLaunchDescription": "diffctl.launch_legacy.include_events",
    "event_named": "diffctl.launch_legacy.include_events",
    "OpaqueCoroutine": "diffctl.launch_legacy.local_actions",
    "ExecuteLocal": "diffctl.launch_legacy.local_actions",
    "Executable": "diffctl.launch_legacy.local_actions",
    "ComposableNode": "diffctl.launch_legacy.composable",
    "ComposableNodeContainer": "diffctl.launch_legacy.composable",
    "LoadComposableNodes": "diffctl.launch_legacy.composable",
    "LifecycleNode": "diffctl.launch_legacy.lifecycle",
    "OnStateTransition": "diffctl.launch_legacy.lifecycle",
    "ChangeState": "diffctl.launch_legacy.lifecycle",
    "StateTransition": "diffctl.launch_legacy.lifecycle",
    "matches_node_name": "diffctl.launch_legacy.lifecycle",
    "SetROSLogDir": "diffctl.launch_legacy.ros_actions",
    "RosTimer": "diffctl.launch_legacy.ros_actions",
    "UnsetLaunchConfiguration": "diffctl.launch_legacy.actions",
    "PushLaunchConfigurations": "diffctl.launch_legacy.actions",
    "PopLaunchConfigurations": "diffctl.launch_legacy.actions",
    "PushEnvironment": "diffctl.launch_legacy.actions",
    "PopEnvironment": "diffctl.launch_legacy.actions",
    "Action": "diffctl.launch_legacy.actions",
    "OnExecutionComplete": "diffctl.launch_legacy.event_handlers",
    "OnActionEventBase": "diffctl.launch_legacy.event_handlers",
    "EventHandler": "diffctl.launch_legacy.event_handlers",
    "BaseEventHandler": "diffctl.launch_legacy.event_handlers",
    "UnregisterEventHandler": "diffctl.launch_legacy.event_handlers",
    "BooleanSubstitution": "diffctl.launch_legacy.logic_substitutions",
    "PathSubstitution": "diffctl.launch_legacy.substitutions",
    "LocalSubstitution": "diffctl.launch_legacy.substitutions",
    "LaunchLogDir": "diffctl.launch_legacy.substitutions",
    "Substitution": "diffctl.launch_legacy.substitutions",
    "Condition": "diffctl.launch_legacy.conditions",
    "AppendEnvironmentVariable": "diffctl.launch_legacy.actions",
    "DeclareLaunchArgument": "diffctl.launch_legacy.actions",
    "GroupAction": "diffctl.launch_legacy.actions",
    "LaunchDescription": "diffctl.launch_legacy.actions",
    "LogInfo": "diffctl.launch_legacy.actions",
    "PushROSNamespace": "diffctl.launch_legacy.actions",
    "PushRosNamespace": "diffctl.launch_legacy.actions",
    "ResetEnvironment": "diffctl.launch_legacy.actions",
    "ResetLaunchConfigurations": "diffctl.launch_legacy.actions",
    "SetEnvironmentVariable": "diffctl.launch_legacy.actions",
    "SetLaunchConfiguration": "diffctl.launch_legacy.actions",
    "Shutdown": "diffctl.launch_legacy.actions",
    "TimerAction": "diffctl.launch_legacy.actions",
    "UnsetEnvironmentVariable": "diffctl.launch_legacy.actions",
    "IfCondition": "diffctl.launch_legacy.conditions",
    "LaunchConfigurationEquals": "diffctl.launch_legacy.conditions",
    "LaunchConfigurationNotEquals": "diffctl.launch_legacy.conditions",
    "UnlessCondition": "diffctl.launch_legacy.conditions",
    "EmitEvent": "diffctl.launch_legacy.event_actions",
    "OpaqueFunction": "diffctl.launch_legacy.event_actions",
    "OnProcessExit": "diffctl.launch_legacy.event_handlers",
    "OnProcessIO": "diffctl.launch_legacy.event_handlers",
    "OnProcessStart": "diffctl.launch_legacy.event_handlers",
    "OnShutdown": "diffctl.launch_legacy.event_handlers",
    "RegisterEventHandler": "diffctl.launch_legacy.event_handlers",
    "AnyLaunchDescriptionSource": "diffctl.launch_legacy.include_action",
    "FrontendLaunchDescriptionSource": "diffctl.launch_legacy.include_action",
    "IncludeLaunchDescription": "diffctl.launch_legacy.include_action",
    "LaunchDescriptionSource": "diffctl.launch_legacy.include_action",
    "PythonLaunchDescriptionSource": "diffctl.launch_legacy.include_action",
    "XMLLaunchDescriptionSource": "diffctl.launch_legacy.include_action",
    "YAMLLaunchDescriptionSource": "diffctl.launch_legacy.include_action",
    "AllSubstitution": "diffctl.launch_legacy.logic_substitutions",
    "AndSubstitution": "diffctl.launch_legacy.logic_substitutions",
    "AnySubstitution": "diffctl.launch_legacy.logic_substitutions",
    "EqualsSubstitution": "diffctl.launch_legacy.logic_substitutions",
    "IfElseSubstitution": "diffctl.launch_legacy.logic_substitutions",
    "NotEqualsSubstitution": "diffctl.launch_legacy.logic_substitutions",
    "NotSubstitution": "diffctl.launch_legacy.logic_substitutions",
    "OrSubstitution": "diffctl.launch_legacy.logic_substitutions",
    "PackageNotFoundError": "diffctl.workspace.package_index",
    "get_package_prefix": "diffctl.workspace.package_index",
    "get_package_share_directory": "diffctl.workspace.package_index",
    "get_package_share_path": "diffctl.workspace.package_index",
    "ParameterFile": "diffctl.launch_legacy.parameters",
    "ParameterValue": "diffctl.launch_legacy.parameters",
    "Parameter": "diffctl.launch_legacy.parameters",
    "ExecuteProcess": "diffctl.launch_legacy.process_actions",
    "Node": "diffctl.launch_legacy.process_actions",
    "WaitFor": "diffctl.launch_legacy.readiness",
    "SetParameter": "diffctl.launch_legacy.ros_actions",
    "SetParametersFromFile": "diffctl.launch_legacy.ros_actions",
    "SetRemap": "diffctl.launch_legacy.ros_actions",
    "SetUseSimTime": "diffctl.launch_legacy.ros_actions",
    "AnonName": "diffctl.launch_legacy.substitutions",
    "Command": "diffctl.launch_legacy.substitutions",
    "EnvironmentVariable": "diffctl.launch_legacy.substitutions",
    "ExecutableInPackage": "diffctl.launch_legacy.substitutions",
    "FileContent": "diffctl.launch_legacy.substitutions",
    "FindExecutable": "diffctl.launch_legacy.substitutions",
    "FindPackagePrefix": "diffctl.launch_legacy.substitutions",
    "FindPackageShare": "diffctl.launch_legacy.substitutions",
    "LaunchConfiguration": "diffctl.launch_legacy.substitutions",
    "PathJoinSubstitution": "diffctl.launch_legacy.substitutions",
    "PythonExpression": "diffctl.launch_legacy.substitutions",
    "TextSubstitution": "diffctl.launch_legacy.substitutions",
    "ThisLaunchFile": "diffctl.launch_legacy.substitutions",
    "ThisLaunchFileDir": "diffctl.launch_legacy.substitutions",
    "get_logger": "diffctl.launch_legacy.user_logging",
}

__all__ = sorted(_ORIGIN)


def __getattr__(name: str) -> object:
    origin = _ORIGIN.get(name)
    if origin is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(origin), name)
    globals()[name] = value  # once imported, a plain module attribute
    return value


def __dir__() -> list[str]:
    return sorted(__all__)
