"""What the launch's fork server preloads for diffctl's components: the CLI layer names them, the engine not.

The fork server (diffctl/supervision/zygote.py) imports these modules once and calls the warm-up functions, then
forks every `python -m diffctl …` component from that state. The lists were measured over a whole
`diffctl launch sim_control` (PYTHONPROFILEIMPORTTIME); the warm-ups are each component's own start-up work.
"""

from __future__ import annotations

from diffctl.supervision.zygote import Preload

# What the sim_control graph's components import at start-up (measured with PYTHONPROFILEIMPORTTIME over a
# whole launch): third-party libraries first, then diffctl's command and component modules. A module that
# fails to import is left to the component, which then fails exactly as it would have without the server.
PRELOAD: tuple[str, ...] = (
    "numpy",
    "numpy.random",
    "yaml",
    "lxml.etree",
    "click",
    "zenoh",
    "rosbags.typesys",
    "pybullet",
    "diffctl.cli.main",
    "diffctl.bus.gz",
    "diffctl.bus.graph",
    "diffctl.bus.participant",
    "diffctl.client.node",
    "diffctl.client.component",
    "diffctl.client.executors",
    "diffctl.client.parameter_service",
    "diffctl.client.type_description_service",
    "diffctl.client.rosout",
    "diffctl.description",
    "diffctl.description.urdf",
    "diffctl.sim.cli",
    "diffctl.sim.runner",
    "diffctl.sim.world",
    "diffctl.sim.sensors",
    "diffctl.sim.plugins",
    "diffctl.sim.world_client",
    "diffctl.sim.services",
    "diffctl.control.manager",
    "diffctl.control.realtime_publisher",
    "diffctl.control.controllers.diff_drive",
    "diffctl.control.controllers.joint_state_broadcaster",
    "diffctl.control.controller_node",
    "diffctl.control.cli",
    "diffctl.control.spawner",
    "diffctl.cli.spawn",
    "diffctl.robot_state_publisher.cli",
    "diffctl.robot_state_publisher.node",
    "diffctl.bridge.cli",
    "diffctl.bridge.bridge",
)
# The bus types the sim_control components use at start-up (recorded over a whole launch): registering a type
# in the typestore builds its classes, and a compiled CDR codec costs 5-15 ms, in every process that uses it —
# 0.4 s of the simulator's gz_ros2_control plugin start and 0.1-0.2 s of each spawner's. Done once here, the
# components inherit them. Services get codecs both ways (the spawner encodes a request, the manager decodes
# it); those only declared at start-up (a node's parameter services) are registered and hashed.
WARM_SERVICES: tuple[str, ...] = (
    "controller_manager_msgs/srv/ListControllers",
    "controller_manager_msgs/srv/LoadController",
    "controller_manager_msgs/srv/ConfigureController",
    "controller_manager_msgs/srv/SwitchController",
    "rcl_interfaces/srv/SetParameters",
)
DECLARED_SERVICES: tuple[str, ...] = (
    "controller_manager_msgs/srv/CleanupController",
    "controller_manager_msgs/srv/ListControllerTypes",
    "controller_manager_msgs/srv/ListHardwareComponents",
    "controller_manager_msgs/srv/ListHardwareInterfaces",
    "controller_manager_msgs/srv/ReloadControllerLibraries",
    "controller_manager_msgs/srv/SetHardwareComponentState",
    "controller_manager_msgs/srv/UnloadController",
    "rcl_interfaces/srv/DescribeParameters",
    "rcl_interfaces/srv/GetParameterTypes",
    "rcl_interfaces/srv/GetParameters",
    "rcl_interfaces/srv/ListParameters",
    "rcl_interfaces/srv/SetParametersAtomically",
    "type_description_interfaces/srv/GetTypeDescription",
)
WARM_MESSAGES: tuple[str, ...] = (
    "rcl_interfaces/msg/Log",
    "rcl_interfaces/msg/ParameterEvent",
    "std_msgs/msg/String",
    "rosgraph_msgs/msg/Clock",
    "sensor_msgs/msg/JointState",
    "tf2_msgs/msg/TFMessage",
    "nav_msgs/msg/Odometry",
    "geometry_msgs/msg/TwistStamped",
    "control_msgs/msg/DynamicJointState",
    "controller_manager_msgs/msg/ControllerManagerActivity",  # every manager publishes it as it comes up
)  # the bridge's sensor types (Imu, LaserScan, Image, CameraInfo: 25 ms) it compiles itself, off the critical path
# The generated classes (and their CDR codecs) every client Node uses as it starts — its parameter services,
# events and descriptors, /rosout, type descriptions — and those the sim_control components publish and take at
# start-up (robot_state_publisher's TF and description, joint states).
CLIENT_MESSAGES: tuple[str, ...] = (
    "rcl_interfaces/msg/ParameterDescriptor",
    "rcl_interfaces/msg/SetParametersResult",
    "rcl_interfaces/msg/ParameterEvent",
    "rcl_interfaces/msg/ListParametersResult",
    "rcl_interfaces/msg/Log",
    "builtin_interfaces/msg/Time",
    "tf2_msgs/msg/TFMessage",
    "geometry_msgs/msg/TransformStamped",
    "std_msgs/msg/String",
    "sensor_msgs/msg/JointState",
    "rosgraph_msgs/msg/Clock",
    # the controller manager's and its controllers' (declarations, ~/activity, diff_drive, joint_state_broadcaster)
    "rcl_interfaces/msg/Parameter",
    "rcl_interfaces/msg/ParameterValue",
    "rcl_interfaces/msg/FloatingPointRange",
    "rcl_interfaces/msg/IntegerRange",
    "controller_manager_msgs/msg/ControllerManagerActivity",
    "nav_msgs/msg/Odometry",
    "geometry_msgs/msg/TwistStamped",
    "control_msgs/msg/DynamicJointState",
    "control_msgs/msg/InterfaceValue",
)
CLIENT_SERVICES: tuple[str, ...] = (
    *(f"controller_manager_msgs/srv/{s}" for s in (
        "ListControllers", "LoadController", "ConfigureController", "SwitchController", "CleanupController",
        "UnloadController", "ListControllerTypes", "ListHardwareComponents", "ListHardwareInterfaces",
        "SetHardwareComponentState", "ReloadControllerLibraries")),
    "rcl_interfaces/srv/GetLoggerLevels",
    "rcl_interfaces/srv/SetLoggerLevels",
    "rcl_interfaces/srv/DescribeParameters",
    "rcl_interfaces/srv/GetParameters",
    "rcl_interfaces/srv/GetParameterTypes",
    "rcl_interfaces/srv/ListParameters",
    "rcl_interfaces/srv/SetParameters",
    "rcl_interfaces/srv/SetParametersAtomically",
    "type_description_interfaces/srv/GetTypeDescription",
)
# Components a launch usually starts only once the robot is up (the visualizer after the spawners, a
# recorder): imported while the server has no request waiting, so they stay off the start-up's critical path.
PRELOAD_LATER: tuple[str, ...] = (
    "diffctl.viz.cli",
    "diffctl.viz.server",
    "diffctl.viz.bus_feed",
    "diffctl.bag.cli",
)


def warm_bus_types() -> None:
    """Register the start-up types in the bus's typestore and compile their codecs (see WARM_MESSAGES)."""
    from diffctl.interfaces import types

    for name in (*WARM_SERVICES, *DECLARED_SERVICES):
        types.type_hash(types.check_service(name))
    for name in WARM_SERVICES:
        for part in ("_Request", "_Response"):
            types.encoder(name + part)
            types.decoder(name + part)
    for name in WARM_MESSAGES:
        types.type_hash(types.check(name))
        types.encoder(name)
        types.decoder(name)


def warm_client_classes() -> None:
    """Generate the client's start-up classes and compile their codecs (see CLIENT_MESSAGES)."""
    from diffctl import interfaces
    from diffctl.client.interfaces import cls

    for name in CLIENT_MESSAGES:
        c = cls(name)
        interfaces.deserialize(interfaces.serialize(c()), c)
    for name in CLIENT_SERVICES:
        srv = cls(name)
        for part in (srv.Request, srv.Response):
            interfaces.deserialize(interfaces.serialize(part()), part)


def scan_controller_plugins() -> None:
    """The installed controller and hardware plugins, scanned once for every controller manager."""
    from diffctl.control import plugin_registry

    plugin_registry.controller_types()
    plugin_registry.hardware_plugins()


def reserve_sim_client() -> None:
    """The simulator's PyBullet client, connected (no thread, nothing loaded)."""
    from diffctl.sim import world

    world.reserve_client()


SPEC = Preload(
    modules=PRELOAD,
    later=PRELOAD_LATER,
    warm=(
        f"{__name__}:warm_bus_types",
        f"{__name__}:warm_client_classes",
        f"{__name__}:scan_controller_plugins",
        f"{__name__}:reserve_sim_client",
    ),
)
