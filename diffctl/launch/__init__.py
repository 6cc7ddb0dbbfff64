"""The launch engine: descriptions (YAML, XML and Python), resolution, and leak-proof process supervision.

Python launch files use these names, as in ROS 2's `launch` / `launch_ros`:

    from diffctl.launch import LaunchDescription, Node, RegisterEventHandler, OnProcessExit

The engine knows processes, not robots: it imports nothing of diffctl but errors and console.
"""

from diffctl.launch.actions import (
    AppendEnvironmentVariable,
    DeclareLaunchArgument,
    GroupAction,
    LaunchDescription,
    LogInfo,
    PushROSNamespace,
    PushRosNamespace,
    ResetEnvironment,
    ResetLaunchConfigurations,
    SetEnvironmentVariable,
    SetLaunchConfiguration,
    Shutdown,
    TimerAction,
    UnsetEnvironmentVariable,
)
from diffctl.launch.conditions import (
    IfCondition,
    LaunchConfigurationEquals,
    LaunchConfigurationNotEquals,
    UnlessCondition,
)
from diffctl.launch.event_actions import EmitEvent, OpaqueFunction
from diffctl.launch.event_handlers import (
    OnProcessExit,
    OnProcessIO,
    OnProcessStart,
    OnShutdown,
    RegisterEventHandler,
)
from diffctl.launch.include_action import (
    AnyLaunchDescriptionSource,
    FrontendLaunchDescriptionSource,
    IncludeLaunchDescription,
    LaunchDescriptionSource,
    PythonLaunchDescriptionSource,
    XMLLaunchDescriptionSource,
    YAMLLaunchDescriptionSource,
)
from diffctl.launch.logic_substitutions import (
    AllSubstitution,
    AndSubstitution,
    AnySubstitution,
    EqualsSubstitution,
    IfElseSubstitution,
    NotEqualsSubstitution,
    NotSubstitution,
    OrSubstitution,
)
from diffctl.launch.package_index import (
    PackageNotFoundError,
    get_package_prefix,
    get_package_share_directory,
    get_package_share_path,
)
from diffctl.launch.parameters import ParameterFile, ParameterValue
from diffctl.launch.process_actions import ExecuteProcess, Node
from diffctl.launch.readiness import WaitFor
from diffctl.launch.ros_actions import SetParameter, SetParametersFromFile, SetRemap, SetUseSimTime
from diffctl.launch.substitutions import (
    AnonName,
    Command,
    EnvironmentVariable,
    ExecutableInPackage,
    FileContent,
    FindExecutable,
    FindPackagePrefix,
    FindPackageShare,
    LaunchConfiguration,
    PathJoinSubstitution,
    PythonExpression,
    TextSubstitution,
    ThisLaunchFile,
    ThisLaunchFileDir,
)

__all__ = [
    "AllSubstitution",
    "AndSubstitution",
    "AnonName",
    "AnyLaunchDescriptionSource",
    "AnySubstitution",
    "AppendEnvironmentVariable",
    "Command",
    "DeclareLaunchArgument",
    "EmitEvent",
    "EnvironmentVariable",
    "EqualsSubstitution",
    "ExecutableInPackage",
    "ExecuteProcess",
    "FileContent",
    "FindExecutable",
    "FindPackagePrefix",
    "FindPackageShare",
    "FrontendLaunchDescriptionSource",
    "GroupAction",
    "IfCondition",
    "IfElseSubstitution",
    "IncludeLaunchDescription",
    "LaunchConfiguration",
    "LaunchConfigurationEquals",
    "LaunchConfigurationNotEquals",
    "LaunchDescription",
    "LaunchDescriptionSource",
    "LogInfo",
    "Node",
    "NotEqualsSubstitution",
    "NotSubstitution",
    "OnProcessExit",
    "OnProcessIO",
    "OnProcessStart",
    "OnShutdown",
    "OpaqueFunction",
    "OrSubstitution",
    "PackageNotFoundError",
    "ParameterFile",
    "ParameterValue",
    "PathJoinSubstitution",
    "PushROSNamespace",
    "PushRosNamespace",
    "PythonExpression",
    "PythonLaunchDescriptionSource",
    "RegisterEventHandler",
    "ResetEnvironment",
    "ResetLaunchConfigurations",
    "SetEnvironmentVariable",
    "SetLaunchConfiguration",
    "SetParameter",
    "SetParametersFromFile",
    "SetRemap",
    "SetUseSimTime",
    "Shutdown",
    "TextSubstitution",
    "ThisLaunchFile",
    "ThisLaunchFileDir",
    "TimerAction",
    "UnlessCondition",
    "UnsetEnvironmentVariable",
    "WaitFor",
    "XMLLaunchDescriptionSource",
    "YAMLLaunchDescriptionSource",
    "get_package_prefix",
    "get_package_share_directory",
    "get_package_share_path",
]
