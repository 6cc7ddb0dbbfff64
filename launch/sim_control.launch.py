"""The tutorial's sim_control_gz.launch.py, as the tutorial writes it.

diffctl resolves `launch`, `launch_ros` and `ament_index_python` to its own classes, and the packages the
tutorial starts to its components: ros_gz_sim's gz_sim.launch.py → the PyBullet simulator (which hosts the
controller manager of every model with the gz_ros2_control plugin, as Gazebo does), create → spawn entity,
controller_manager spawner, ros_gz_bridge, rviz2 → the browser visualizer. Additions to the tutorial's file:
the arguments gui, viz, viz_port, world and rtf, and paths of this repository's layout.
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch.actions import (
    DeclareLaunchArgument,
    ExecuteProcess,
    IncludeLaunchDescription,
    LogInfo,
    RegisterEventHandler,
)
from launch.conditions import IfCondition, UnlessCondition
from launch.event_handlers import OnProcessExit
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

from launch import LaunchDescription


def generate_launch_description():
    # Get the package share directory
    robot_description = get_package_share_directory("diffctl_demo_description")
    simulation_package = get_package_share_directory("diffctl_demo")

    # Define the path to RViz, and SDF files
    rviz_file = os.path.join(simulation_package, "config", "diffbot.rviz")
    gazebo_launch_file = os.path.join(get_package_share_directory("ros_gz_sim"), "launch", "gz_sim.launch.py")
    sdf_file = os.path.join(robot_description, "my_diff_car_control.sdf")

    # Path to controller file
    controller_config_path = os.path.join(simulation_package, "config", "diff_drive_controller.yaml")

    # Read the robot description file and replace the PARAMETERS_CONFIG_FILE_PLACEHOLDER with the controller file
    with open(sdf_file) as f:
        robot_description_content = f.read().replace("PARAMETERS_CONFIG_FILE_PLACEHOLDER", controller_config_path)
    use_sim_time = LaunchConfiguration("use_sim_time")
    robot_description = {"robot_description": robot_description_content, "use_sim_time": use_sim_time}

    # bridge config file
    bridge_params = os.path.join(simulation_package, "config", "bridge_config_control.yaml")

    joint_state_broadcaster_spawner = Node(
        package="controller_manager",
        executable="spawner",
        arguments=["joint_state_broadcaster"],
    )
    robot_controller_spawner = Node(
        package="controller_manager",
        executable="spawner",
        arguments=["diffbot_base_controller", "--param-file", controller_config_path],
    )

    # Define the robot_state_publisher node (relays only: it comes back if it dies)
    robot_state_publisher_node = Node(
        package="robot_state_publisher",
        executable="robot_state_publisher",
        output="screen",
        parameters=[robot_description],
        respawn=True,
        respawn_delay=1.0,
    )

    # Define the RViz node (the browser visualizer)
    rviz_node = Node(
        package="rviz2",
        executable="rviz2",
        name="rviz2",
        output="screen",
        arguments=["-d", rviz_file, "--port", LaunchConfiguration("viz_port")],
        parameters=[{"use_sim_time": True}],
        respawn=True,
        respawn_delay=1.0,
        condition=IfCondition(LaunchConfiguration("viz")),
    )

    world_file = LaunchConfiguration("world")
    rtf = LaunchConfiguration("rtf")

    # Define the Gazebo node server (with gui:=true, the server with its PyBullet window)
    gazebo_node = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(gazebo_launch_file),
        launch_arguments={
            "gz_args": [" -r -s -v4 --rtf ", rtf, " ", world_file],
            "on_exit_shutdown": "true",
        }.items(),
        condition=UnlessCondition(LaunchConfiguration("gui")),
    )
    gazebo_with_window = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(gazebo_launch_file),
        launch_arguments={
            "gz_args": [" -r --gui -v4 --rtf ", rtf, " ", world_file],
            "on_exit_shutdown": "true",
        }.items(),
        condition=IfCondition(LaunchConfiguration("gui")),
    )

    # Gazebo GUI (the browser visualizer shows the scene; the GUI client alone starts nothing)
    gzclient_cmd = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(os.path.join(gazebo_launch_file)),
        launch_arguments={"gz_args": "-g -v4 "}.items(),
    )

    # Define the spawn_entity node to spawn the robot in Gazebo
    spawn_entity_node = Node(
        package="ros_gz_sim",
        executable="create",
        arguments=["-topic", "/robot_description", "-name", "robot"],
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

    delay_rviz_after_joint_state_broadcaster_spawner = RegisterEventHandler(
        event_handler=OnProcessExit(
            target_action=joint_state_broadcaster_spawner,
            on_exit=[
                LogInfo(
                    msg="controllers active. Drive the car: diffctl topic pub cmd_vel "
                    "'{twist: {linear: {x: 0.5}, angular: {z: 0.3}}}' --rate 10"
                ),
                rviz_node,
            ],
        )
    )
    delay_joint_state_broadcaster_after_robot_controller_spawner = RegisterEventHandler(
        event_handler=OnProcessExit(
            target_action=robot_controller_spawner,
            on_exit=[joint_state_broadcaster_spawner],
        )
    )

    return LaunchDescription(
        [
            DeclareLaunchArgument(
                "use_sim_time",
                default_value="true",
                description="Use simulation (Gazebo) clock if true",
            ),
            DeclareLaunchArgument(
                "gui", default_value="false", choices=["true", "false"],
                description="Open the PyBullet window (Gazebo's GUI)",
            ),
            DeclareLaunchArgument(
                "viz", default_value="true", choices=["true", "false"],
                description="Start the browser visualizer (RViz2)",
            ),
            DeclareLaunchArgument("viz_port", default_value="8080", description="Port of the visualizer's web page"),
            DeclareLaunchArgument(
                "world", default_value=os.path.join(simulation_package, "config", "worlds", "empty.world"),
                description="SDF world file",
            ),
            DeclareLaunchArgument(
                "rtf", default_value="1", description="Real-time factor target; 0 runs as fast as possible"
            ),
            DeclareLaunchArgument(
                "record", default_value="false", choices=["true", "false"],
                description="Record the topics with diffctl bag record (camera images left out) next to the logs",
            ),
            robot_state_publisher_node,
            robot_controller_spawner,
            gazebo_node,
            gazebo_with_window,
            gzclient_cmd,
            spawn_entity_node,
            start_gazebo_ros_bridge_cmd,
            delay_joint_state_broadcaster_after_robot_controller_spawner,
            delay_rviz_after_joint_state_broadcaster_spawner,
            # ros2 bag record; the camera is rendered on demand, so its images are left out.
            ExecuteProcess(
                cmd=["diffctl", "bag", "record", "-a", "--exclude-regex", "^/camera/"], name="bag_record",
                output="screen", condition=IfCondition(LaunchConfiguration("record")),
            ),
        ]
    )
