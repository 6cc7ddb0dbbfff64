"""A throw-away ROS 2 workspace shaped like the tutorial's, as a user's clone of it looks on disk.

Two ament_cmake packages under src/ — diff_sim (launch, config, worlds, installed by a CMake
`install(DIRECTORY … DESTINATION share/${PROJECT_NAME})` rule) and robot_description (sdf/, installed the same way) —
the tutorial's launch file text, its controller and bridge YAML, an SDF robot whose camera is an 800×600
100 Hz rgbd_camera, and stale build/ install/ log/ folders from the author's machine whose symlinks point nowhere.
"""

from __future__ import annotations

import os
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
DATA = Path(__file__).resolve().parent / "data"

PACKAGE_XML = """<?xml version="1.0"?>
<?xml-model href="http://download.ros.org/schema/package_format3.xsd" schematypens="http://www.w3.org/2001/XMLSchema"?>
<package format="3">
  <name>{name}</name>
  <version>0.0.1</version>
  <description>{name} of the diff-drive tutorial</description>
  <maintainer email="someone@example.com">someone</maintainer>
  <license>Apache-2.0</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <exec_depend>ros_gz_sim</exec_depend>
  <exec_depend>ros_gz_bridge</exec_depend>
  <exec_depend>controller_manager</exec_depend>
  <export>
    <build_type>ament_cmake</build_type>
  </export>
</package>
"""

CMAKE = """cmake_minimum_required(VERSION 3.8)
project({name})

if(CMAKE_COMPILER_IS_GNUCXX OR CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  add_compile_options(-Wall -Wextra -Wpedantic)
endif()

find_package(ament_cmake REQUIRED)

install(
  DIRECTORY {dirs}
  DESTINATION share/${{PROJECT_NAME}}
)

ament_package()
"""

BRIDGE = """# bridge_config_control_gz.yaml: what the controllers do not publish themselves
- ros_topic_name: "/clock"
  gz_topic_name: "/clock"
  ros_type_name: "rosgraph_msgs/msg/Clock"
  gz_type_name: "gz.msgs.Clock"
  direction: GZ_TO_ROS
- ros_topic_name: "/scan"
  gz_topic_name: "/lidar"
  ros_type_name: "sensor_msgs/msg/LaserScan"
  gz_type_name: "gz.msgs.LaserScan"
  direction: GZ_TO_ROS
- ros_topic_name: "/imu"
  gz_topic_name: "/imu"
  ros_type_name: "sensor_msgs/msg/Imu"
  gz_type_name: "gz.msgs.IMU"
  direction: GZ_TO_ROS
- topic_name: "/camera/image"
  ros_type_name: "sensor_msgs/msg/Image"
  gz_type_name: "gz.msgs.Image"
  direction: GZ_TO_ROS
- topic_name: "/camera/depth_image"
  ros_type_name: "sensor_msgs/msg/Image"
  gz_type_name: "gz.msgs.Image"
  direction: GZ_TO_ROS
- topic_name: "/camera/points"
  ros_type_name: "sensor_msgs/msg/PointCloud2"
  gz_type_name: "gz.msgs.PointCloudPacked"
  direction: GZ_TO_ROS
- topic_name: "/camera/camera_info"
  ros_type_name: "sensor_msgs/msg/CameraInfo"
  gz_type_name: "gz.msgs.CameraInfo"
  direction: GZ_TO_ROS
"""

RGBD = """<sensor name="rgbd_camera" type="rgbd_camera">
        <pose>0.011 0 0 0 0 0</pose>
        <topic>camera</topic>
        <gz_frame_id>camera_link</gz_frame_id>
        <update_rate>100</update_rate>
        <always_on>true</always_on>
        <visualize>true</visualize>
        <camera>
          <horizontal_fov>1.047</horizontal_fov>
          <image><width>800</width><height>600</height><format>R8G8B8</format></image>
          <clip><near>0.05</near><far>10</far></clip>
        </camera>
      </sensor>"""

# The mock-hardware variant a user writes next to it: the same robot, no simulator.
MOCK_LAUNCH = '''import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import RegisterEventHandler
from launch.event_handlers import OnProcessExit
from launch_ros.actions import Node


def generate_launch_description():
    robot_description = get_package_share_directory("robot_description")
    simulation_package = get_package_share_directory("diff_sim")
    sdf_file = os.path.join(robot_description, "sdf", "my_diff_car_control_gz.sdf")
    controller_config_path = os.path.join(simulation_package, "config", "diff_drive_controller.yaml")
    robot_description_content = (
        open(sdf_file, "r").read()
        .replace("PARAMETERS_CONFIG_FILE_PLACEHOLDER", controller_config_path)
        .replace("gz_ros2_control/GazeboSimSystem", "mock_components/GenericSystem")
    )
    control_node = Node(
        package="controller_manager",
        executable="ros2_control_node",
        parameters=[controller_config_path, {"use_sim_time": False}],
        output="screen",
    )
    robot_state_publisher_node = Node(
        package="robot_state_publisher",
        executable="robot_state_publisher",
        output="screen",
        parameters=[{"robot_description": robot_description_content}],
    )
    joint_state_broadcaster_spawner = Node(
        package="controller_manager", executable="spawner", arguments=["joint_state_broadcaster"]
    )
    robot_controller_spawner = Node(
        package="controller_manager",
        executable="spawner",
        arguments=["diffbot_base_controller", "--param-file", controller_config_path],
    )
    return LaunchDescription([
        control_node,
        robot_state_publisher_node,
        robot_controller_spawner,
        RegisterEventHandler(OnProcessExit(target_action=robot_controller_spawner,
                                           on_exit=[joint_state_broadcaster_spawner])),
    ])
'''


def tutorial_launch_text() -> str:
    """The tutorial's sim_control_gz.launch.py, as its text stands on the tutorial's page (data/: the page's code
    block, copied verbatim)."""
    # The tutorial page lost its indentation; put Python's back from the structure of the code.
    return _reindent((DATA / "sim_control_gz.launch.txt").read_text())


def _reindent(flat: str) -> str:
    """Module lines at the left margin, the function body one level in: enough for this file, whose body has
    no nested blocks (inside brackets Python ignores indentation)."""
    out: list[str] = []
    inside = False
    for raw in flat.splitlines():
        line = raw.strip()
        if not line:
            continue
        out.append(("    " if inside else "") + line)
        inside = inside or line.startswith("def ")
    return "\n".join(out) + "\n"


def build(root: Path) -> Path:
    """The workspace at root/ws; returns its root."""
    ws = root / "ws"
    sim = ws / "src" / "diff_sim"
    desc = ws / "src" / "robot_description"
    for d in (sim / "launch", sim / "config", sim / "worlds", desc / "sdf"):
        d.mkdir(parents=True)
    (sim / "package.xml").write_text(PACKAGE_XML.format(name="diff_sim"))
    (sim / "CMakeLists.txt").write_text(CMAKE.format(name="diff_sim", dirs="launch config worlds"))
    (desc / "package.xml").write_text(PACKAGE_XML.format(name="robot_description"))
    (desc / "CMakeLists.txt").write_text(CMAKE.format(name="robot_description", dirs="sdf"))
    (sim / "launch" / "sim_control_gz.launch.py").write_text(tutorial_launch_text())
    (sim / "launch" / "mock_control.launch.py").write_text(MOCK_LAUNCH)
    controllers = (REPO / "config" / "diff_drive_controller.yaml").read_text()
    (sim / "config" / "diff_drive_controller.yaml").write_text(controllers)
    (sim / "config" / "bridge_config_control_gz.yaml").write_text(BRIDGE)
    (sim / "config" / "rviz_config.rviz").write_text((REPO / "config" / "diffbot.rviz").read_text())
    (sim / "worlds" / "empty.world").write_text((REPO / "config" / "worlds" / "empty.world").read_text())
    sdf = (REPO / "description" / "my_diff_car_control.sdf").read_text()
    start = sdf.index('<sensor name="camera" type="camera">')
    end = sdf.index("</sensor>", start) + len("</sensor>")
    (desc / "sdf" / "my_diff_car_control_gz.sdf").write_text(sdf[:start] + RGBD + sdf[end:])
    # Stale colcon output from the author's machine: symlinks into a home directory that is not here.
    for pkg, files in (("diff_sim", ("launch", "config", "worlds")), ("robot_description", ("sdf",))):
        share = ws / "install" / pkg / "share" / pkg
        share.mkdir(parents=True)
        for f in files:
            os.symlink(f"/home/author/ws/src/{pkg}/{f}", share / f)
        marker = ws / "install" / pkg / "share" / "ament_index" / "resource_index" / "packages"
        marker.mkdir(parents=True)
        (marker / pkg).write_text("")
    (ws / "build" / "diff_sim").mkdir(parents=True)
    (ws / "build" / "diff_sim" / "CMakeCache.txt").write_text("CMAKE_HOME_DIRECTORY:INTERNAL=/home/author/ws/src\n")
    (ws / "log" / "latest_build").mkdir(parents=True)
    (ws / "install" / "setup.bash").write_text("# generated by colcon on the author's machine\n")
    return ws
