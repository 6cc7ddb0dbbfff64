"""A ros2_control demo bringup written in XML (and in Python), in a throw-away workspace, run as `ros2 launch`
would run it.

Three ament_cmake packages under src/: `wheel_parts` (a xacro wheel macro), `demo_description` (the robot,
including the wheel macro across packages with `$(find wheel_parts)`, and a `<ros2_control>` block whose
hardware is mock_components/GenericSystem when `use_mock_hardware` is true) and `demo_bringup` (the XML
launch file and the controllers' YAML). The launch file starts robot_state_publisher with the URDF from
`$(command 'xacro …')`, a controller manager named `my_ctrl_mgr`, and spawners with `-c my_ctrl_mgr`,
`--param-file` and `--controller-ros-args '-r ~/cmd_vel:=/cmd_vel'`; the test drives on /cmd_vel.
"""

from __future__ import annotations

import signal
import time
from pathlib import Path

import pytest

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3">
  <name>{name}</name>
  <version>0.1.0</version>
  <description>{name}</description>
  <maintainer email="someone@example.com">someone</maintainer>
  <license>Apache-2.0</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <export><build_type>ament_cmake</build_type></export>
</package>
"""

CMAKE = """cmake_minimum_required(VERSION 3.8)
project({name})
find_package(ament_cmake REQUIRED)
install(DIRECTORY {dirs} DESTINATION share/${{PROJECT_NAME}})
ament_package()
"""

WHEEL_XACRO = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="wheel" params="side y radius">
    <link name="${side}_wheel">
      <visual><geometry><cylinder radius="${radius}" length="0.04"/></geometry></visual>
      <collision><geometry><cylinder radius="${radius}" length="0.04"/></geometry></collision>
      <inertial><mass value="0.2"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
    </link>
    <joint name="${side}_wheel_joint" type="continuous">
      <parent link="base_link"/>
      <child link="${side}_wheel"/>
      <origin xyz="0 ${y} 0" rpy="-1.5708 0 0"/>
      <axis xyz="0 0 1"/>
    </joint>
  </xacro:macro>
</robot>
"""

ROBOT_XACRO = """<?xml version="1.0"?>
<robot name="demo_bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="use_mock_hardware" default="false"/>
  <xacro:property name="separation" value="0.3"/>
  <xacro:property name="radius" value="0.05"/>
  <xacro:include filename="$(find wheel_parts)/urdf/wheel.xacro"/>
  <link name="base_link">
    <visual><geometry><box size="0.4 0.25 0.1"/></geometry></visual>
    <inertial><mass value="2.0"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <xacro:wheel side="left" y="${separation / 2}" radius="${radius}"/>
  <xacro:wheel side="right" y="${-separation / 2}" radius="${radius}"/>
  <ros2_control name="DemoBotSystem" type="system">
    <hardware>
      <xacro:if value="$(arg use_mock_hardware)">
        <plugin>mock_components/GenericSystem</plugin>
        <param name="calculate_dynamics">true</param>
      </xacro:if>
      <xacro:unless value="$(arg use_mock_hardware)">
        <plugin>demo_hardware/DemoBotSystemHardware</plugin>
      </xacro:unless>
    </hardware>
    <joint name="left_wheel_joint">
      <command_interface name="velocity"/>
      <state_interface name="position"/>
      <state_interface name="velocity"/>
    </joint>
    <joint name="right_wheel_joint">
      <command_interface name="velocity"/>
      <state_interface name="position"/>
      <state_interface name="velocity"/>
    </joint>
  </ros2_control>
</robot>
"""

CONTROLLERS = """my_ctrl_mgr:
  ros__parameters:
    update_rate: 50

diff_cont:
  ros__parameters:
    type: diff_drive_controller/DiffDriveController
    left_wheel_names: ["left_wheel_joint"]
    right_wheel_names: ["right_wheel_joint"]
    wheel_separation: 0.3
    wheel_radius: 0.05
    publish_rate: 50.0
    base_frame_id: base_link
    cmd_vel_timeout: 0.5

joint_broad:
  ros__parameters:
    type: joint_state_broadcaster/JointStateBroadcaster
"""

BRINGUP = """<launch>
  <arg name="use_mock_hardware" default="false" description="Start the robot with mock hardware"/>
  <arg name="start_drive" default="true"/>
  <let name="xacro_file" value="$(find-pkg-share demo_description)/urdf/demo_bot.urdf.xacro"/>
  <let name="robot_description"
       value="$(command 'xacro $(var xacro_file) use_mock_hardware:=$(var use_mock_hardware)')"/>
  <let name="controllers" value="$(find-pkg-share demo_bringup)/config/demo_controllers.yaml"/>

  <node pkg="robot_state_publisher" exec="robot_state_publisher" output="both">
    <param name="robot_description" value="$(var robot_description)" type="str"/>
  </node>

  <node pkg="controller_manager" exec="ros2_control_node" name="my_ctrl_mgr" output="both">
    <param from="$(var controllers)"/>
    <remap from="~/robot_description" to="/robot_description"/>
  </node>

  <node pkg="controller_manager" exec="spawner" args="joint_broad -c my_ctrl_mgr --param-file $(var controllers)"/>
  <node pkg="controller_manager" exec="spawner" if="$(var start_drive)"
        args="diff_cont -c my_ctrl_mgr --param-file $(var controllers) --controller-ros-args '-r ~/cmd_vel:=/cmd_vel'"/>
</launch>
"""


# The same bringup as ros2_control_demos writes it in Python.
BRINGUP_PY = """
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, RegisterEventHandler
from launch.conditions import IfCondition
from launch.event_handlers import OnProcessExit
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    use_mock_hardware = LaunchConfiguration("use_mock_hardware")
    robot_description_content = Command([
        PathJoinSubstitution([FindExecutable(name="xacro")]), " ",
        PathJoinSubstitution([FindPackageShare("demo_description"), "urdf", "demo_bot.urdf.xacro"]), " ",
        "use_mock_hardware:=", use_mock_hardware,
    ])
    robot_description = {"robot_description": ParameterValue(robot_description_content, value_type=str)}
    controllers = PathJoinSubstitution([FindPackageShare("demo_bringup"), "config", "demo_controllers.yaml"])
    control_node = Node(package="controller_manager", executable="ros2_control_node", name="my_ctrl_mgr",
                        parameters=[controllers], remappings=[("~/robot_description", "/robot_description")],
                        output="both")
    rsp = Node(package="robot_state_publisher", executable="robot_state_publisher", output="both",
               parameters=[robot_description])
    jsb_spawner = Node(package="controller_manager", executable="spawner",
                       arguments=["joint_broad", "-c", "my_ctrl_mgr", "--param-file", controllers])
    drive_spawner = Node(package="controller_manager", executable="spawner",
                         arguments=["diff_cont", "-c", "my_ctrl_mgr", "--param-file", controllers,
                                    "--controller-ros-args", "-r ~/cmd_vel:=/cmd_vel"],
                         condition=IfCondition(LaunchConfiguration("start_drive")))
    return LaunchDescription([
        DeclareLaunchArgument("use_mock_hardware", default_value="false"),
        DeclareLaunchArgument("start_drive", default_value="true"),
        control_node,
        rsp,
        jsb_spawner,
        RegisterEventHandler(OnProcessExit(target_action=jsb_spawner, on_exit=[drive_spawner])),
    ])
"""


def make_workspace(root: Path) -> Path:
    ws = root / "demo_ws"
    packages = {
        "wheel_parts": {"urdf/wheel.xacro": WHEEL_XACRO},
        "demo_description": {"urdf/demo_bot.urdf.xacro": ROBOT_XACRO},
        "demo_bringup": {
            "launch/demo.launch.xml": BRINGUP,
            "launch/demo.launch.py": BRINGUP_PY,
            "config/demo_controllers.yaml": CONTROLLERS,
        },
    }
    for name, files in packages.items():
        pkg = ws / "src" / name
        dirs = sorted({f.split("/")[0] for f in files})
        for rel, text in files.items():
            (pkg / rel).parent.mkdir(parents=True, exist_ok=True)
            (pkg / rel).write_text(text)
        (pkg / "package.xml").write_text(PACKAGE_XML.format(name=name))
        (pkg / "CMakeLists.txt").write_text(CMAKE.format(name=name, dirs=" ".join(dirs)))
    return ws


@pytest.mark.slow
@pytest.mark.parametrize("launch_file", ["demo.launch.xml", "demo.launch.py"])
def test_a_bringup_with_xacro_across_packages_drives_on_mock_hardware(
    launch_file: str, router, launch_run, tmp_path
) -> None:
    from tests.probe import Probe

    ws = make_workspace(tmp_path)
    run = launch_run("demo_bringup", launch_file, "use_mock_hardware:=true", cwd=ws)
    node = Probe("xml_bringup_test")
    try:
        odom_x: list[float] = []
        node.create_subscription(
            "/diff_cont/odom", "nav_msgs/msg/Odometry", lambda m: odom_x.append(m.pose.pose.position.x)
        )
        joints: list[list[str]] = []
        node.create_subscription("/joint_states", "sensor_msgs/msg/JointState", lambda m: joints.append(list(m.name)))
        states = node.create_client("/my_ctrl_mgr/list_controllers", "controller_manager_msgs/srv/ListControllers")

        def active() -> bool:
            assert run.proc.poll() is None, run.text()
            if not states.wait_for_service(timeout=0.5):
                return False
            got = {c.name: c.state for c in states.call({}, timeout=5.0).controller}
            return got.get("diff_cont") == "active" and got.get("joint_broad") == "active"

        deadline = time.monotonic() + 300
        while not active():
            assert time.monotonic() < deadline, f"controllers never became active:\n{run.text()}"
            time.sleep(0.2)
        # The manager loaded the xacro-expanded URDF's mock hardware, with the wheel macro from the other package.
        assert "'DemoBotSystem' (mock_components/GenericSystem) is active" in run.text(), run.text()

        cmd = node.create_publisher("/cmd_vel", "geometry_msgs/msg/TwistStamped")
        twist = {"header": {"stamp": {"sec": 0, "nanosec": 0}}, "twist": {"linear": {"x": 0.4}}}
        deadline = time.monotonic() + 180
        while not (odom_x and odom_x[-1] > 0.2):
            assert time.monotonic() < deadline, f"odometry never moved (last {odom_x[-1:]})\n{run.text()}"
            cmd.publish(twist)
            time.sleep(0.05)
        assert joints and {"left_wheel_joint", "right_wheel_joint"} <= set(joints[-1])
    finally:
        node.close()
    run.signal(signal.SIGINT)
    assert run.wait(120) == 0, run.text()
    assert run.leftovers() == []
