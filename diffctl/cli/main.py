"""Entry point of `diffctl`: maps every subcommand to the package that owns it and reports errors.

Any `DiffctlError` that escapes a command is printed as one line and turned into its exit code; a
traceback reaching the user is a bug.
"""

from __future__ import annotations

import sys

import click

from diffctl import __version__
from diffctl.cli.lazy import LazyGroup

COMMANDS: dict[str, tuple[str, str]] = {
    "router": ("diffctl.cli.router:router", "Run a Zenoh router alone (rmw_zenohd)."),
    "topic": ("diffctl.cli.topic:topic", "List, echo, publish, measure topics (ros2 topic)."),
    "node": ("diffctl.cli.graph:node", "List nodes and show what they publish and serve (ros2 node)."),
    "service": ("diffctl.cli.graph:service", "List and call services (ros2 service)."),
    "param": ("diffctl.cli.param:param", "List, get, set, describe, dump and load node parameters (ros2 param)."),
    "interface": ("diffctl.cli.graph:interface", "Show message and service definitions (ros2 interface)."),
    "lifecycle": ("diffctl.cli.lifecycle:lifecycle", "Get, set and list states of managed nodes (ros2 lifecycle)."),
    "launch": ("diffctl.cli.launch:launch", "Start a launch file and supervise it (ros2 launch)."),
    "sim": ("diffctl.sim.cli:sim", "Run the PyBullet simulator on an SDF world (gz sim)."),
    "spawn": ("diffctl.cli.spawn:spawn", "Spawn an entity into the sim or a controller into the manager."),
    "robot-state-publisher": (
        "diffctl.robot_state_publisher.cli:robot_state_publisher",
        "Publish /robot_description and TF from joint states.",
    ),
    "control": ("diffctl.control.cli:control", "Controller manager and its commands (ros2 control)."),
    "bridge": ("diffctl.bridge.cli:bridge", "Bridge simulator topics to ROS topics (ros_gz_bridge)."),
    "image-bridge": ("diffctl.bridge.image_bridge_cli:image_bridge", "Bridge gz image topics to ROS (ros_gz_image)."),
    "viz": ("diffctl.viz.cli:viz", "Browser visualizer (rviz2)."),
    "teleop": ("diffctl.teleop.cli:teleop", "Drive the robot from a keyboard or a game pad."),
    "run": ("diffctl.cli.run:run", "Run a package's executable: the user's Python nodes from sources (ros2 run)."),
    "pkg": ("diffctl.cli.pkg:pkg", "List packages and where they were found (ros2 pkg)."),
    "joint-state-publisher": (
        "diffctl.joint_state_publisher.cli:joint_state_publisher",
        "Publish the non-fixed joints of /robot_description (joint_state_publisher).",
    ),
    "bag": ("diffctl.bag.cli:bag", "Record and replay rosbag2 MCAP bags (ros2 bag)."),
    "foxglove-bridge": ("diffctl.foxglove.cli:foxglove_bridge", "Foxglove WebSocket server (foxglove_bridge)."),
    "description": ("diffctl.cli.description:description", "Show what the simulator makes of a URDF/xacro/SDF."),
    "fuel": ("diffctl.fuel.cli:fuel", "Download Gazebo Fuel models into Gazebo's cache (gz fuel)."),
    "tf2": ("diffctl.tf2_tools.cli:tf2", "tf2_ros's static_transform_publisher and tf2_echo."),
    "robot-localization": (
        "diffctl.robot_localization.cli:robot_localization",
        "robot_localization's ekf_node, ukf_node and navsat_transform_node.",
    ),
    "topic-tools": (
        "diffctl.topic_tools.cli:topic_tools",
        "topic_tools' relay, throttle, drop, delay, mux, demux and relay_field.",
    ),
    "twist-mux": ("diffctl.twist_mux.cli:twist_mux", "twist_mux: velocity commands by priority, timeouts and locks."),
    "twist-stamper": (
        "diffctl.twist_stamper.cli:twist_stamper",
        "twist_stamper's twist_stamper and twist_unstamper (Twist <-> TwistStamped).",
    ),
    "joy-teleop": ("diffctl.joy_teleop.cli:joy_teleop", "joy_teleop: Joy messages to configured topics and calls."),
    "joy": ("diffctl.joy.cli:joy", "joy's joy_node: a joystick on sensor_msgs/Joy."),
    "teleop-twist-keyboard": (
        "diffctl.teleop.cli:teleop_twist_keyboard",
        "teleop_twist_keyboard: keys to Twist/TwistStamped on cmd_vel.",
    ),
    "interactive-marker-twist-server": (
        "diffctl.interactive_marker_twist_server.cli:interactive_marker_twist_server",
        "interactive_marker_twist_server's marker_server: an RViz marker dragged into Twist.",
    ),
    "laser-filters": (
        "diffctl.laser_filters.cli:laser_filters",
        "laser_filters' scan_to_scan_filter_chain: LaserScan filter chains.",
    ),
    "key-teleop": ("diffctl.key_teleop.cli:key_teleop", "key_teleop: arrow keys in a terminal to key_vel."),
    "teleop-twist-joy": (
        "diffctl.teleop_twist_joy.cli:teleop_twist_joy",
        "teleop_twist_joy's teleop_node: Joy to Twist/TwistStamped on cmd_vel.",
    ),
    "joy-linux": ("diffctl.joy_linux.cli:joy_linux", "joy_linux's joy_linux_node: /dev/input/jsX on sensor_msgs/Joy."),
    "ros2-controllers-test-nodes": (
        "diffctl.ros2_controllers_test_nodes.cli:ros2_controllers_test_nodes",
        "ros2_controllers_test_nodes' goal publishers (forward position, joint trajectory).",
    ),
    "test": ("diffctl.testing.cli:test", "Run launch tests and pytest files (launch_test, colcon test)."),
    "test-child": ("diffctl.testing.cli:test_child", "(internal) one launch test forked by `diffctl test -j`."),
    "component-container": (
        "diffctl.cli.component_container:component_container",
        "Host Python composable nodes in one process (rclcpp_components' component_container).",
    ),
}


@click.group(cls=LazyGroup, lazy_commands=COMMANDS, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, "--version", prog_name="diffctl")
def cli() -> None:
    """diffctl: launch, simulate, control and watch a differential-drive robot, ROS 2 style, without ROS.

    \b
    Example:
      diffctl launch sim_control
      diffctl topic pub cmd_vel '{twist: {linear: {x: 0.5}}}' --rate 10
    """


def _limit_malloc_arenas() -> None:
    # glibc gives each thread that allocates its own 64 MB malloc arena; Zenoh's and the node's threads
    # would otherwise add tens of MB of resident memory per process, times seven processes per launch.
    try:
        import ctypes

        ctypes.CDLL("libc.so.6").mallopt(-8, 2)  # M_ARENA_MAX = 2
    except (OSError, AttributeError):
        pass


def main(argv: list[str] | None = None) -> None:
    from diffctl import ros_args

    _limit_malloc_arenas()
    from diffctl.errors import DiffctlError

    argv, ros = ros_args.split_argv(sys.argv[1:] if argv is None else list(argv))
    ros_args.set_current(ros)
    try:
        rv = cli.main(args=argv, prog_name="diffctl", standalone_mode=False)
        if isinstance(rv, int) and not isinstance(rv, bool):
            _close_bus()
            sys.exit(rv)
    except click.exceptions.Abort:
        sys.exit(130)
    except click.exceptions.Exit as e:
        sys.exit(e.exit_code)
    except click.ClickException as e:
        e.show()
        sys.exit(e.exit_code)
    except DiffctlError as e:
        from diffctl.console import error

        error(str(e))
        sys.exit(e.exit_code)
    except KeyboardInterrupt:
        sys.exit(130)
    except BrokenPipeError:
        sys.exit(0)
    finally:
        _close_bus()
    sys.exit(0)


def _close_bus() -> None:
    # Only when a command used the bus: importing zenoh just to close nothing would slow every command.
    session = sys.modules.get("diffctl.bus.session")
    if session is not None:
        session.close_session()
