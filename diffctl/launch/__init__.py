"""The launch engine: descriptions (YAML, XML and Python), resolution, and leak-proof process supervision.

Python launch files use these names, as in ROS 2's `launch` / `launch_ros`:

    from diffctl.launch import LaunchDescription, Node, RegisterEventHandler, OnProcessExit

The engine knows processes, not robots: it imports nothing of diffctl but errors and console.
The names are imported on first use (PEP 562): the fork server (`python -m diffctl.launch.zygote`) and the
forked components import this package but none of the engine, which costs 0.2-0.3 s to import.
"""

from __future__ import annotations

import importlib

# Every public name and the module it lives in: the one list (`__all__` is derived from it).
_ORIGIN: dict[str, str] = {
    "FindPackage": "diffctl.launch.ros_substitutions",
    "LifecycleTransition": "diffctl.launch.lifecycle_transition",
    "OnIncludeLaunchDescription": "diffctl.launch.include_events",
    "event_named": "diffctl.launch.include_events",
    "OpaqueCoroutine": "diffctl.launch.local_actions",
    "ExecuteLocal": "diffctl.launch.local_actions",
    "Executable": "diffctl.launch.local_actions",
    "ComposableNode": "diffctl.launch.composable",
    "ComposableNodeContainer": "diffctl.launch.composable",
    "LoadComposableNodes": "diffctl.launch.composable",
    "LifecycleNode": "diffctl.launch.lifecycle",
    "OnStateTransition": "diffctl.launch.lifecycle",
    "ChangeState": "diffctl.launch.lifecycle",
    "StateTransition": "diffctl.launch.lifecycle",
    "matches_node_name": "diffctl.launch.lifecycle",
    "SetROSLogDir": "diffctl.launch.ros_actions",
    "RosTimer": "diffctl.launch.ros_actions",
    "UnsetLaunchConfiguration": "diffctl.launch.actions",
    "PushLaunchConfigurations": "diffctl.launch.actions",
    "PopLaunchConfigurations": "diffctl.launch.actions",
    "PushEnvironment": "diffctl.launch.actions",
    "PopEnvironment": "diffctl.launch.actions",
    "Action": "diffctl.launch.actions",
    "OnExecutionComplete": "diffctl.launch.event_handlers",
    "OnActionEventBase": "diffctl.launch.event_handlers",
    "EventHandler": "diffctl.launch.event_handlers",
    "BaseEventHandler": "diffctl.launch.event_handlers",
    "UnregisterEventHandler": "diffctl.launch.event_handlers",
    "BooleanSubstitution": "diffctl.launch.logic_substitutions",
    "PathSubstitution": "diffctl.launch.substitutions",
    "LocalSubstitution": "diffctl.launch.substitutions",
    "LaunchLogDir": "diffctl.launch.substitutions",
    "Substitution": "diffctl.launch.substitutions",
    "Condition": "diffctl.launch.conditions",
    "AppendEnvironmentVariable": "diffctl.launch.actions",
    "DeclareLaunchArgument": "diffctl.launch.actions",
    "GroupAction": "diffctl.launch.actions",
    "LaunchDescription": "diffctl.launch.actions",
    "LogInfo": "diffctl.launch.actions",
    "PushROSNamespace": "diffctl.launch.actions",
    "PushRosNamespace": "diffctl.launch.actions",
    "ResetEnvironment": "diffctl.launch.actions",
    "ResetLaunchConfigurations": "diffctl.launch.actions",
    "SetEnvironmentVariable": "diffctl.launch.actions",
    "SetLaunchConfiguration": "diffctl.launch.actions",
    "Shutdown": "diffctl.launch.actions",
    "TimerAction": "diffctl.launch.actions",
    "UnsetEnvironmentVariable": "diffctl.launch.actions",
    "IfCondition": "diffctl.launch.conditions",
    "LaunchConfigurationEquals": "diffctl.launch.conditions",
    "LaunchConfigurationNotEquals": "diffctl.launch.conditions",
    "UnlessCondition": "diffctl.launch.conditions",
    "EmitEvent": "diffctl.launch.event_actions",
    "OpaqueFunction": "diffctl.launch.event_actions",
    "OnProcessExit": "diffctl.launch.event_handlers",
    "OnProcessIO": "diffctl.launch.event_handlers",
    "OnProcessStart": "diffctl.launch.event_handlers",
    "OnShutdown": "diffctl.launch.event_handlers",
    "RegisterEventHandler": "diffctl.launch.event_handlers",
    "AnyLaunchDescriptionSource": "diffctl.launch.include_action",
    "FrontendLaunchDescriptionSource": "diffctl.launch.include_action",
    "IncludeLaunchDescription": "diffctl.launch.include_action",
    "LaunchDescriptionSource": "diffctl.launch.include_action",
    "PythonLaunchDescriptionSource": "diffctl.launch.include_action",
    "XMLLaunchDescriptionSource": "diffctl.launch.include_action",
    "YAMLLaunchDescriptionSource": "diffctl.launch.include_action",
    "AllSubstitution": "diffctl.launch.logic_substitutions",
    "AndSubstitution": "diffctl.launch.logic_substitutions",
    "AnySubstitution": "diffctl.launch.logic_substitutions",
    "EqualsSubstitution": "diffctl.launch.logic_substitutions",
    "IfElseSubstitution": "diffctl.launch.logic_substitutions",
    "NotEqualsSubstitution": "diffctl.launch.logic_substitutions",
    "NotSubstitution": "diffctl.launch.logic_substitutions",
    "OrSubstitution": "diffctl.launch.logic_substitutions",
    "PackageNotFoundError": "diffctl.workspace.package_index",
    "get_package_prefix": "diffctl.workspace.package_index",
    "get_package_share_directory": "diffctl.workspace.package_index",
    "get_package_share_path": "diffctl.workspace.package_index",
    "ParameterFile": "diffctl.launch.parameters",
    "ParameterValue": "diffctl.launch.parameters",
    "Parameter": "diffctl.launch.parameters",
    "ExecuteProcess": "diffctl.launch.process_actions",
    "Node": "diffctl.launch.process_actions",
    "WaitFor": "diffctl.launch.readiness",
    "SetParameter": "diffctl.launch.ros_actions",
    "SetParametersFromFile": "diffctl.launch.ros_actions",
    "SetRemap": "diffctl.launch.ros_actions",
    "SetUseSimTime": "diffctl.launch.ros_actions",
    "AnonName": "diffctl.launch.substitutions",
    "Command": "diffctl.launch.substitutions",
    "EnvironmentVariable": "diffctl.launch.substitutions",
    "ExecutableInPackage": "diffctl.launch.substitutions",
    "FileContent": "diffctl.launch.substitutions",
    "FindExecutable": "diffctl.launch.substitutions",
    "FindPackagePrefix": "diffctl.launch.substitutions",
    "FindPackageShare": "diffctl.launch.substitutions",
    "LaunchConfiguration": "diffctl.launch.substitutions",
    "PathJoinSubstitution": "diffctl.launch.substitutions",
    "PythonExpression": "diffctl.launch.substitutions",
    "TextSubstitution": "diffctl.launch.substitutions",
    "ThisLaunchFile": "diffctl.launch.substitutions",
    "ThisLaunchFileDir": "diffctl.launch.substitutions",
    "get_logger": "diffctl.launch.user_logging",
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
