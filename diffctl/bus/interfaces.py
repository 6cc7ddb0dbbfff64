"""ROS 2 Jazzy interface definitions that rosbags' Jazzy store lacks, as their .msg/.srv text.

Field order and types follow the Jazzy releases of controller_manager_msgs, control_msgs and std_srvs,
because the RIHS01 type hash (and so the rmw_zenoh key) is computed from them.
"""

from __future__ import annotations

MSGS: dict[str, str] = {
    "controller_manager_msgs/msg/ChainConnection": """
string name
string[] reference_interfaces
""",
    "controller_manager_msgs/msg/ControllerState": """
string name
string state
string type
bool is_async
uint16 update_rate
string[] claimed_interfaces
string[] required_command_interfaces
string[] required_state_interfaces
bool is_chainable
bool is_chained
string[] exported_state_interfaces
string[] reference_interfaces
controller_manager_msgs/ChainConnection[] chain_connections
""",
    # ros-controls/ros2_control, branch `jazzy` (controller_manager_msgs 4.x as released for Jazzy and published at
    # docs.ros.org/en/jazzy/p/controller_manager_msgs): HardwareInterface has no `data_type` (that field is
    # Kilted/Rolling only) and HardwareComponentState keeps the deprecated `class_type` between rw_rate and
    # plugin_name. rosidl's Jazzy build of these two gives HardwareComponentState
    # RIHS01_0ed49e3b2669d3a540536dd4806a301612d0daf93a25bb1eebfd55817416026d, checked in tests/graph.
    "controller_manager_msgs/msg/HardwareInterface": """
string name
bool is_available
bool is_claimed
""",
    "controller_manager_msgs/msg/HardwareComponentState": """
string name
string type
bool is_async
uint16 rw_rate
string class_type
string plugin_name
lifecycle_msgs/State state
controller_manager_msgs/HardwareInterface[] command_interfaces
controller_manager_msgs/HardwareInterface[] state_interfaces
""",
    # ros-controls/control_msgs 5.x as released for Jazzy (docs.ros.org/en/jazzy/p/control_msgs): unchanged
    # since 4.0 in these two types.
    "control_msgs/msg/InterfaceValue": """
string[] interface_names
float64[] values
""",
    "control_msgs/msg/DynamicJointState": """
std_msgs/Header header
string[] joint_names
control_msgs/InterfaceValue[] interface_values
""",
}

_OK = "bool ok"

SRVS: dict[str, tuple[str, str]] = {
    "controller_manager_msgs/srv/ListControllers": ("", "controller_manager_msgs/ControllerState[] controller"),
    "controller_manager_msgs/srv/ListControllerTypes": ("", "string[] types\nstring[] base_classes"),
    "controller_manager_msgs/srv/ListHardwareComponents": (
        "",
        "controller_manager_msgs/HardwareComponentState[] component",
    ),
    "controller_manager_msgs/srv/ListHardwareInterfaces": (
        "",
        "controller_manager_msgs/HardwareInterface[] command_interfaces\n"
        "controller_manager_msgs/HardwareInterface[] state_interfaces",
    ),
    "controller_manager_msgs/srv/LoadController": ("string name", _OK),
    "controller_manager_msgs/srv/ConfigureController": ("string name", _OK),
    "controller_manager_msgs/srv/UnloadController": ("string name", _OK),
    "controller_manager_msgs/srv/CleanupController": ("string name", _OK),
    "controller_manager_msgs/srv/ReloadControllerLibraries": ("bool force_kill", _OK),
    "controller_manager_msgs/srv/SwitchController": (
        "string[] activate_controllers\nstring[] deactivate_controllers\nint32 strictness\n"
        "int32 BEST_EFFORT=1\nint32 STRICT=2\nint32 AUTO=3\nint32 FORCE_AUTO=4\n"
        "bool activate_asap\nbuiltin_interfaces/Duration timeout",
        "bool ok\nstring message",
    ),
    "controller_manager_msgs/srv/SetHardwareComponentState": (
        "string name\nlifecycle_msgs/State target_state",
        "bool ok\nlifecycle_msgs/State state",
    ),
    # Parameter services of every node (rclcpp); the spawner sets `<ctrl>.type` / `.params_file` through them.
    "rcl_interfaces/srv/SetParameters": ("rcl_interfaces/Parameter[] parameters",
                                         "rcl_interfaces/SetParametersResult[] results"),
    "rcl_interfaces/srv/GetParameters": ("string[] names", "rcl_interfaces/ParameterValue[] values"),
    "rcl_interfaces/srv/ListParameters": ("string[] prefixes\nuint64 depth\nuint64 DEPTH_RECURSIVE=0",
                                          "rcl_interfaces/ListParametersResult result"),
    "rcl_interfaces/srv/SetParametersAtomically": ("rcl_interfaces/Parameter[] parameters",
                                                   "rcl_interfaces/SetParametersResult result"),
    "rcl_interfaces/srv/DescribeParameters": ("string[] names", "rcl_interfaces/ParameterDescriptor[] descriptors"),
    "rcl_interfaces/srv/GetParameterTypes": ("string[] names", "uint8[] types"),
    # Every node's ~/get_type_description (REP-2016); the request's default (include_type_sources=true) is not
    # part of the type hash.
    "type_description_interfaces/srv/GetTypeDescription": (
        "string type_name\nstring type_hash\nbool include_type_sources",
        "bool successful\nstring failure_reason\ntype_description_interfaces/TypeDescription type_description\n"
        "type_description_interfaces/TypeSource[] type_sources\n"
        "type_description_interfaces/KeyValue[] extra_information",
    ),
    "std_srvs/srv/Empty": ("", ""),
    "std_srvs/srv/Trigger": ("", "bool success\nstring message"),
    "std_srvs/srv/SetBool": ("bool data", "bool success\nstring message"),
}
