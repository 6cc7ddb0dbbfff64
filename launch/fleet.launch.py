"""Several tutorial cars in one simulated world, each in its own namespace with its own controller manager.

    diffctl launch fleet robots:=3 [rtf:=1] [viz:=true] [spacing:=1.5] [gui:=false]

Written as a ROS 2 user writes a multi-robot gz_ros2_control launch file, with public launch features only:
an OpaqueFunction reads `robots`, and for every robot K a GroupAction with PushRosNamespace("robotK") holds
its robot_state_publisher (frame_prefix "robotK/"), its `create` (-topic robot_description resolves in the
namespace) and its spawners (`-c /robotK/controller_manager`). Each robot's description is the tutorial's
control SDF with the placeholder replaced, `<ros><namespace>/robotK</namespace></ros>` added to the
gz_ros2_control plugin (so the simulator hosts /robotK/controller_manager and its controllers publish
/robotK/diffbot_base_controller/odom and TF robotK/odom → robotK/base_footprint), and every sensor `<topic>`
prefixed with "robotK/": Gazebo publishes a `<topic>` as written (a relative one at the root), so two cars
with `<topic>lidar</topic>` would share one topic; `<gz_frame_id>`s get the same prefix as the TF frames.
One bridge carries /clock and each robot's sensors
(gz robotK/lidar → /robotK/scan, …) from one config written at launch time. One visualizer shows every car:
its .rviz is config/diffbot.rviz with the topic displays repeated in a group per robot (topics under /robotK,
RobotModel with TF Prefix robotK) and the fixed frame `world`; the teleop panel picks which car to drive.
"""

import atexit
import copy
import math
import os
import tempfile
import xml.etree.ElementTree as ET

import yaml
from launch.actions import (
    DeclareLaunchArgument,
    GroupAction,
    IncludeLaunchDescription,
    OpaqueFunction,
    RegisterEventHandler,
)
from launch.conditions import IfCondition, UnlessCondition
from launch.event_handlers import OnProcessExit
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node, PushRosNamespace

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription

# The tutorial car's sensors by SDF type: the ROS topic (in the robot's namespace) and bridged types.
SENSOR_BRIDGES = {
    "gpu_lidar": ("scan", "sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan", False),
    "lidar": ("scan", "sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan", False),
    "imu": ("imu", "sensor_msgs/msg/Imu", "gz.msgs.IMU", False),
    # Cameras are rendered on demand: the bridge asks for frames only while someone subscribes.
    "camera": ("camera/image_raw", "sensor_msgs/msg/Image", "gz.msgs.Image", True),
}
PLUGIN_FILENAMES = ("gz_ros2_control-system", "libgz_ros2_control-system", "libgz_ros2_control-system.so")


def robot_description(template: str, namespace: str) -> tuple[str, list[dict]]:
    """The description of one robot in `namespace`, and the bridge entries of its sensors."""
    root = ET.fromstring(template)
    for plugin in root.iter("plugin"):
        if plugin.get("filename") in PLUGIN_FILENAMES:
            ros = plugin.find("ros")
            if ros is None:
                ros = ET.SubElement(plugin, "ros")
            ns = ros.find("namespace")
            if ns is None:
                ns = ET.SubElement(ros, "namespace")
            ns.text = "/" + namespace
    entries = []
    for sensor in root.iter("sensor"):
        # A message's frame is <gz_frame_id> as written: prefixed like robot_state_publisher's TF frames.
        frame = sensor.find("gz_frame_id")
        if frame is not None and (frame.text or "").strip():
            frame.text = f"{namespace}/{frame.text.strip()}"
        topic = sensor.find("topic")
        if topic is None or not (topic.text or "").strip():
            continue  # Gazebo's default topic already holds the model name
        gz_topic = f"/{namespace}/{topic.text.strip().lstrip('/')}"
        topic.text = gz_topic
        bridge = SENSOR_BRIDGES.get(sensor.get("type", ""))
        if bridge is None:
            continue
        ros_name, ros_type, gz_type, lazy = bridge
        entries.append(
            {
                "ros_topic_name": f"/{namespace}/{ros_name}",
                "gz_topic_name": gz_topic,
                "ros_type_name": ros_type,
                "gz_type_name": gz_type,
                "direction": "GZ_TO_ROS",
                "lazy": lazy,
            }
        )
    return ET.tostring(root, encoding="unicode"), entries


def grid_xy(index: int, count: int, spacing_m: float) -> tuple[float, float]:
    """Robot `index` (0-based) of `count` on a square grid, rows along +x: robot2 is in front of robot1."""
    columns = max(1, math.ceil(math.sqrt(count)))
    return (index % columns) * spacing_m, (index // columns) * spacing_m


def _topic_key(display: dict) -> str | None:
    for key in ("Description Topic", "Topic"):
        value = display.get(key)
        if isinstance(value, dict):
            value = value.get("Value")
        if isinstance(value, str) and value.startswith("/"):
            return key
    return None


def fleet_rviz(template_file: str, namespaces: list[str]) -> str:
    """The .rviz text of the fleet: displays without a topic once, the others once per robot in a group."""
    with open(template_file) as f:
        config = yaml.safe_load(f)
    manager = config["Visualization Manager"]
    displays = manager.get("Displays") or []
    shared = [d for d in displays if _topic_key(d) is None]
    per_robot = [d for d in displays if _topic_key(d) is not None]
    groups = []
    for ns in namespaces:
        children = []
        for d in per_robot:
            c = copy.deepcopy(d)
            key = _topic_key(c)
            if isinstance(c[key], dict):
                c[key]["Value"] = f"/{ns}{c[key]['Value']}"
            else:
                c[key] = f"/{ns}{c[key]}"
            if c.get("Class") == "rviz_default_plugins/RobotModel":
                c["TF Prefix"] = ns
            children.append(c)
        groups.append({"Class": "rviz_common/Group", "Name": ns, "Enabled": True, "Displays": children})
    manager["Displays"] = shared + groups
    manager.setdefault("Global Options", {})["Fixed Frame"] = "world"
    return yaml.safe_dump(config, sort_keys=False)


def _written(text: str, suffix: str) -> str:
    fd, path = tempfile.mkstemp(prefix="diffctl_fleet_", suffix=suffix)
    with os.fdopen(fd, "w") as f:
        f.write(text)
    atexit.register(lambda: os.path.exists(path) and os.remove(path))
    return path


def fleet(context):
    description_dir = get_package_share_directory("diffctl_demo_description")
    share = get_package_share_directory("diffctl_demo")
    controllers = LaunchConfiguration("controllers_file").perform(context)
    count_text = LaunchConfiguration("robots").perform(context)
    spacing_text = LaunchConfiguration("spacing").perform(context)
    try:
        count = int(count_text)
    except ValueError:
        count = 0
    if not 1 <= count <= 50:
        raise ValueError(f"robots:={count_text!r} must be a whole number from 1 to 50")
    try:
        spacing_m = float(spacing_text)
    except ValueError:
        spacing_m = float("nan")
    if not (math.isfinite(spacing_m) and spacing_m >= 0.5):
        raise ValueError(f"spacing:={spacing_text!r} must be a distance in metres of at least 0.5")
    use_sim_time = LaunchConfiguration("use_sim_time")
    with open(os.path.join(description_dir, "my_diff_car_control.sdf")) as f:
        template = f.read().replace("PARAMETERS_CONFIG_FILE_PLACEHOLDER", controllers)

    actions = []
    bridge_entries = [
        {
            "ros_topic_name": "/clock",
            "gz_topic_name": "/clock",
            "ros_type_name": "rosgraph_msgs/msg/Clock",
            "gz_type_name": "gz.msgs.Clock",
            "direction": "GZ_TO_ROS",
        }
    ]
    for k in range(1, count + 1):
        ns = f"robot{k}"
        description, entries = robot_description(template, ns)
        bridge_entries += entries
        x_m, y_m = grid_xy(k - 1, count, spacing_m)
        diff_spawner = Node(
            package="controller_manager",
            executable="spawner",
            name="spawner_diffbot_base_controller",
            # Given here too: an event handler's actions run after the group's PushRosNamespace is gone.
            namespace=f"/{ns}",
            arguments=[
                "diffbot_base_controller", "joint_state_broadcaster",
                "-c", f"/{ns}/controller_manager", "--param-file", controllers,
            ],
            output="screen",
        )
        create = Node(
            package="ros_gz_sim",
            executable="create",
            arguments=["-topic", "robot_description", "-name", ns, "-x", str(x_m), "-y", str(y_m)],
            output="screen",
        )
        actions.append(
            GroupAction(
                [
                    PushRosNamespace(ns),
                    Node(
                        package="robot_state_publisher",
                        executable="robot_state_publisher",
                        parameters=[
                            {"robot_description": description, "use_sim_time": use_sim_time,
                             "frame_prefix": f"{ns}/"}
                        ],
                        respawn=True,
                        respawn_delay=1.0,
                    ),
                    create,
                    # The spawner starts once its car is in the world: spawners take turns (a machine-wide
                    # lock), and one waiting for a manager that does not exist yet would hold up the others.
                    RegisterEventHandler(OnProcessExit(target_action=create, on_exit=[diff_spawner])),
                ]
            )
        )
    bridge_file = _written(yaml.safe_dump(bridge_entries, sort_keys=False), ".bridge.yaml")
    actions.append(
        Node(
            package="ros_gz_bridge",
            executable="parameter_bridge",
            arguments=["--ros-args", "-p", f"config_file:={bridge_file}"],
            output="screen",
            respawn=True,
            respawn_delay=1.0,
        )
    )
    namespaces = [f"robot{k}" for k in range(1, count + 1)]
    rviz_file = _written(fleet_rviz(os.path.join(share, "config", "diffbot.rviz"), namespaces), ".rviz")
    actions.append(
        Node(
            package="rviz2",
            executable="rviz2",
            name="rviz2",
            output="screen",
            arguments=["-d", rviz_file, "--port", LaunchConfiguration("viz_port"),
                       "--teleop-topic", "/robot1/diffbot_base_controller/cmd_vel"],
            parameters=[{"use_sim_time": use_sim_time}],
            respawn=True,
            respawn_delay=1.0,
            condition=IfCondition(LaunchConfiguration("viz")),
        )
    )
    return actions


def generate_launch_description():
    share = get_package_share_directory("diffctl_demo")
    gazebo_launch_file = os.path.join(get_package_share_directory("ros_gz_sim"), "launch", "gz_sim.launch.py")
    world_file = LaunchConfiguration("world")
    rtf = LaunchConfiguration("rtf")
    return LaunchDescription(
        [
            DeclareLaunchArgument("robots", default_value="3", description="How many cars (robot1 … robotN)"),
            DeclareLaunchArgument("spacing", default_value="1.5", description="Grid spacing of the cars in metres"),
            DeclareLaunchArgument("use_sim_time", default_value="true", description="Use the simulation clock"),
            DeclareLaunchArgument(
                "gui", default_value="false", choices=["true", "false"],
                description="Open the PyBullet window (Gazebo's GUI)",
            ),
            DeclareLaunchArgument(
                "viz", default_value="true", choices=["true", "false"],
                description="Start the browser visualizer (RViz2) showing every car",
            ),
            DeclareLaunchArgument("viz_port", default_value="8080", description="Port of the visualizer's web page"),
            DeclareLaunchArgument(
                "world", default_value=os.path.join(share, "config", "worlds", "empty.world"),
                description="SDF world file",
            ),
            DeclareLaunchArgument(
                "rtf", default_value="1", description="Real-time factor target; 0 runs as fast as possible"
            ),
            DeclareLaunchArgument(
                "controllers_file", default_value=os.path.join(share, "config", "fleet_controllers.yaml"),
                description="ros2_control parameters of every car's controller manager and controllers "
                "(sections under /**/ or /robotK/: the cars' nodes are namespaced)",
            ),
            IncludeLaunchDescription(
                PythonLaunchDescriptionSource(gazebo_launch_file),
                launch_arguments={"gz_args": [" -r -s --rtf ", rtf, " ", world_file],
                                  "on_exit_shutdown": "true"}.items(),
                condition=UnlessCondition(LaunchConfiguration("gui")),
            ),
            IncludeLaunchDescription(
                PythonLaunchDescriptionSource(gazebo_launch_file),
                launch_arguments={"gz_args": [" -r --gui --rtf ", rtf, " ", world_file],
                                  "on_exit_shutdown": "true"}.items(),
                condition=IfCondition(LaunchConfiguration("gui")),
            ),
            OpaqueFunction(function=fleet),
        ]
    )
