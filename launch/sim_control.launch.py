"""The tutorial's sim_control_gz.launch.py, kept as close to the original as diffctl allows.

diffctl resolves `launch`, `launch_ros` and `ament_index_python` to its own classes, and the package
names to its components (ros_gz_sim → the PyBullet sim, controller_manager → diffctl's manager, rviz2 →
the browser visualizer). Differences from the tutorial: the controller manager runs as its own process
(gz_ros2_control runs it inside Gazebo), and the arguments gui, viz, viz_port, world, rtf exist.
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch.actions import DeclareLaunchArgument, LogInfo, RegisterEventHandler
from launch.conditions import IfCondition, UnlessCondition
from launch.event_handlers import OnProcessExit
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from launch import LaunchDescription


def generate_launch_description():
    robot_description = get_package_share_directory("diffctl_demo_description")
    simulation_package = get_package_share_directory("diffctl_demo")
    rviz_file = os.path.join(simulation_package, "config", "diffbot.rviz")
    sdf_file = os.path.join(robot_description, "my_diff_car_control.sdf")
    controller_config_path = os.path.join(simulation_package, "config", "diff_drive_controller.yaml")
    bridge_params = os.path.join(simulation_package, "config", "bridge_config_control.yaml")

    # Read the robot description and replace the placeholder with the controller file, as the tutorial does.
    with open(sdf_file) as f:
        robot_description_content = f.read().replace("PARAMETERS_CONFIG_FILE_PLACEHOLDER", controller_config_path)

    use_sim_time = LaunchConfiguration("use_sim_time")
    gui = LaunchConfiguration("gui")
    world = LaunchConfiguration("world")
    rtf = LaunchConfiguration("rtf")

    robot_state_publisher_node = Node(
        package="robot_state_publisher",
        executable="robot_state_publisher",
        output="screen",
        parameters=[{"robot_description": robot_description_content, "use_sim_time": use_sim_time}],
        respawn=True,
        respawn_delay=1.0,
    )
    gazebo_server = Node(
        package="ros_gz_sim", executable="gz_sim", name="gz_sim",
        arguments=["-r", "-s", "--rtf", rtf, world], on_exit="shutdown", condition=UnlessCondition(gui),
    )
    gazebo_with_gui = Node(
        package="ros_gz_sim", executable="gz_sim", name="gz_sim",
        arguments=["-r", "--gui", "--rtf", rtf, world], on_exit="shutdown", condition=IfCondition(gui),
    )
    spawn_entity_node = Node(
        package="ros_gz_sim",
        executable="create",
        arguments=["-topic", "/robot_description", "-name", "robot"],
        output="screen",
    )
    controller_manager = Node(
        package="controller_manager",
        executable="ros2_control_node",
        name="controller_manager",
        output="screen",
        parameters=[{"use_sim_time": use_sim_time}],
        on_exit="shutdown",
    )
    robot_controller_spawner = Node(
        package="controller_manager",
        executable="spawner",
        name="spawner_diffbot_base_controller",
        arguments=["diffbot_base_controller", "--param-file", controller_config_path],
        output="screen",
    )
    joint_state_broadcaster_spawner = Node(
        package="controller_manager",
        executable="spawner",
        name="spawner_joint_state_broadcaster",
        arguments=["joint_state_broadcaster"],
        output="screen",
    )
    start_gazebo_ros_bridge_cmd = Node(
        package="ros_gz_bridge",
        executable="parameter_bridge",
        arguments=["--ros-args", "-p", f"config_file:={bridge_params}"],
        output="screen",
        respawn=True,
        respawn_delay=1.0,
    )
    rviz_node = Node(
        package="rviz2",
        executable="rviz2",
        name="rviz2",
        output="screen",
        arguments=["-d", rviz_file, "--port", LaunchConfiguration("viz_port")],
        parameters=[{"use_sim_time": use_sim_time}],
        respawn=True,
        respawn_delay=1.0,
        condition=IfCondition(LaunchConfiguration("viz")),
    )
    delay_joint_state_broadcaster_after_robot_controller_spawner = RegisterEventHandler(
        event_handler=OnProcessExit(
            target_action=robot_controller_spawner,
            on_exit=[joint_state_broadcaster_spawner],
        )
    )
    delay_rviz_after_joint_state_broadcaster_spawner = RegisterEventHandler(
        event_handler=OnProcessExit(
            target_action=joint_state_broadcaster_spawner,
            exit_code=0,
            on_exit=[
                LogInfo(msg="controllers active. Drive the car: diffctl topic pub cmd_vel "
                            "'{twist: {linear: {x: 0.5}, angular: {z: 0.3}}}' --rate 10"),
                rviz_node,
            ],
        )
    )
    return LaunchDescription(
        [
            DeclareLaunchArgument("use_sim_time", default_value="true",
                                  description="Use simulation (Gazebo) clock if true"),
            DeclareLaunchArgument("gui", default_value="false", choices=["true", "false"],
                                  description="Open the PyBullet window (Gazebo's GUI)"),
            DeclareLaunchArgument("viz", default_value="true", choices=["true", "false"],
                                  description="Start the browser visualizer (RViz2)"),
            DeclareLaunchArgument("viz_port", default_value="8080", description="Port of the visualizer's web page"),
            DeclareLaunchArgument("world", default_value=os.path.join(simulation_package, "config", "worlds",
                                                                      "empty.world"),
                                  description="SDF world file"),
            DeclareLaunchArgument("rtf", default_value="1",
                                  description="Real-time factor target; 0 runs as fast as possible"),
            robot_state_publisher_node,
            gazebo_server,
            gazebo_with_gui,
            spawn_entity_node,
            controller_manager,
            robot_controller_spawner,
            start_gazebo_ros_bridge_cmd,
            delay_joint_state_broadcaster_after_robot_controller_spawner,
            delay_rviz_after_joint_state_broadcaster_spawner,
        ]
    )
