"""The tutorial's sim_control_gz.launch.py, nearly verbatim, resolved through diffctl's package index."""

import os

from ament_index_python.packages import get_package_share_directory
from launch.actions import (
    DeclareLaunchArgument,
    GroupAction,
    LogInfo,
    RegisterEventHandler,
    SetEnvironmentVariable,
    Shutdown,
    TimerAction,
)
from launch.conditions import IfCondition
from launch.event_handlers import OnProcessExit
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node, PushRosNamespace

from diffctl.launch_legacy import WaitFor
from launch import LaunchDescription


def generate_launch_description():
    robot_description = get_package_share_directory("diffctl_demo_description")
    simulation_package = get_package_share_directory("diffctl_demo")
    rviz_file = os.path.join(simulation_package, "config", "diffbot.rviz")
    sdf_file = os.path.join(robot_description, "my_diff_car_control.sdf")
    controller_config_path = os.path.join(simulation_package, "config", "diff_drive_controller.yaml")
    with open(sdf_file) as f:
        robot_description_content = f.read().replace("PARAMETERS_CONFIG_FILE_PLACEHOLDER", controller_config_path)
    bridge_params = os.path.join(simulation_package, "config", "bridge_config_control.yaml")
    world_file = os.path.join(simulation_package, "config", "worlds", "empty.world")

    joint_state_broadcaster_spawner = Node(
        package="controller_manager", executable="spawner", arguments=["joint_state_broadcaster"]
    )
    robot_controller_spawner = Node(
        package="controller_manager",
        executable="spawner",
        arguments=["diffbot_base_controller", "--param-file", controller_config_path],
        wait_for=[WaitFor.service("/controller_manager/list_controllers")],
        wait_timeout=30,
    )
    robot_state_publisher_node = Node(
        package="robot_state_publisher",
        executable="robot_state_publisher",
        output="screen",
        parameters=[
            {"robot_description": robot_description_content, "use_sim_time": LaunchConfiguration("use_sim_time")}
        ],
    )
    rviz_node = Node(
        package="rviz2",
        executable="rviz2",
        name="rviz2",
        output="screen",
        arguments=["-d", rviz_file],
        parameters=[{"use_sim_time": True}],
        condition=IfCondition(LaunchConfiguration("gui")),
    )
    gazebo_node = Node(
        package="ros_gz_sim", executable="gz_sim", arguments=["-r", "-s", world_file], on_exit=Shutdown()
    )
    spawn_entity_node = Node(
        package="ros_gz_sim",
        executable="create",
        arguments=["-topic", "/robot_description", "-name", "robot"],
        output="screen",
        wait_for=[WaitFor.topic("/robot_description")],
    )
    start_gazebo_ros_bridge_cmd = Node(
        package="ros_gz_bridge",
        executable="parameter_bridge",
        arguments=["--ros-args", "-p", f"config_file:={bridge_params}"],
        output="screen",
    )
    return LaunchDescription(
        [
            DeclareLaunchArgument(
                "use_sim_time", default_value="true", description="Use simulation (Gazebo) clock if true"
            ),
            DeclareLaunchArgument(
                "gui", default_value="false", description="open the visualizer", choices=["true", "false"]
            ),
            SetEnvironmentVariable("GZ_VERBOSITY", "4"),
            robot_state_publisher_node,
            robot_controller_spawner,
            gazebo_node,
            spawn_entity_node,
            start_gazebo_ros_bridge_cmd,
            RegisterEventHandler(
                OnProcessExit(target_action=robot_controller_spawner, on_exit=[joint_state_broadcaster_spawner])
            ),
            RegisterEventHandler(OnProcessExit(target_action=joint_state_broadcaster_spawner, on_exit=[rviz_node])),
            GroupAction(
                [
                    PushRosNamespace("diagnostics"),
                    Node(
                        package="diffctl",
                        executable="router",
                        respawn=True,
                        respawn_delay=2.0,
                        respawn_max_retries=3,
                        remappings=[("chatter", "/talk")],
                        sigterm_timeout=1.0,
                    ),
                ]
            ),
            TimerAction(
                period=3.0,
                actions=[LogInfo(msg=["launched ", LaunchConfiguration("robot_description_len", default="the car")])],
            ),
        ]
    )
