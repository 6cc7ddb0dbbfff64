"""The launch engine: descriptions (YAML and Python), resolution, and leak-proof process supervision.

Python launch files use these names, as in ROS 2's `launch` / `launch_ros`:

    from diffctl.launch import LaunchDescription, Node, RegisterEventHandler, OnProcessExit

The engine knows processes, not robots: it imports nothing of diffctl but errors and console.
"""

from diffctl.launch.actions import (
    AnyLaunchDescriptionSource,
    DeclareLaunchArgument,
    EmitEvent,
    FrontendLaunchDescriptionSource,
    GroupAction,
    IncludeLaunchDescription,
    LaunchDescription,
    LaunchDescriptionSource,
    LogInfo,
    PushROSNamespace,
    PushRosNamespace,
    PythonLaunchDescriptionSource,
    SetEnvironmentVariable,
    SetLaunchConfiguration,
    Shutdown,
    TimerAction,
    UnsetEnvironmentVariable,
    YAMLLaunchDescriptionSource,
)
from diffctl.launch.conditions import (
    IfCondition,
    LaunchConfigurationEquals,
    LaunchConfigurationNotEquals,
    UnlessCondition,
)
from diffctl.launch.event_handlers import OnProcessExit, OnProcessStart, OnShutdown, RegisterEventHandler
from diffctl.launch.package_index import get_package_share_directory
from diffctl.launch.process_actions import ExecuteProcess, Node, ParameterValue
from diffctl.launch.readiness import WaitFor
from diffctl.launch.substitutions import (
    AnonName,
    Command,
    EnvironmentVariable,
    EqualsSubstitution,
    FileContent,
    FindPackageShare,
    LaunchConfiguration,
    NotSubstitution,
    PathJoinSubstitution,
    PythonExpression,
    TextSubstitution,
    ThisLaunchFile,
    ThisLaunchFileDir,
)

__all__ = [
    "AnonName",
    "AnyLaunchDescriptionSource",
    "Command",
    "DeclareLaunchArgument",
    "EmitEvent",
    "EnvironmentVariable",
    "EqualsSubstitution",
    "ExecuteProcess",
    "FileContent",
    "FindPackageShare",
    "FrontendLaunchDescriptionSource",
    "GroupAction",
    "IfCondition",
    "IncludeLaunchDescription",
    "LaunchConfiguration",
    "LaunchConfigurationEquals",
    "LaunchConfigurationNotEquals",
    "LaunchDescription",
    "LaunchDescriptionSource",
    "LogInfo",
    "Node",
    "NotSubstitution",
    "OnProcessExit",
    "OnProcessStart",
    "OnShutdown",
    "ParameterValue",
    "PathJoinSubstitution",
    "PushROSNamespace",
    "PushRosNamespace",
    "PythonExpression",
    "PythonLaunchDescriptionSource",
    "RegisterEventHandler",
    "SetEnvironmentVariable",
    "SetLaunchConfiguration",
    "Shutdown",
    "TextSubstitution",
    "ThisLaunchFile",
    "ThisLaunchFileDir",
    "TimerAction",
    "UnlessCondition",
    "UnsetEnvironmentVariable",
    "WaitFor",
    "YAMLLaunchDescriptionSource",
    "get_package_share_directory",
]
