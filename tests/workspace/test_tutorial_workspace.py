"""The tutorial as its reader has it: packages `robot_description` and `diff_sim` in ~/ros2_ws/src, built
with colcon in ROS — here read straight from the sources, and winning over diffctl's own demo packages."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

from tests.launch_requests import started
from tests.workspace.conftest import package_xml, write_tree

REPO = Path(__file__).resolve().parents[2]

# The tutorial's sim_control_gz.launch.py (its text, indented as a reader's editor keeps it).
TUTORIAL_LAUNCH = '''
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch_ros.actions import Node
from launch.actions import IncludeLaunchDescription, RegisterEventHandler
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.event_handlers import OnProcessExit
import os
from ament_index_python.packages import get_package_share_directory


def generate_launch_description():
    robot_description = get_package_share_directory("robot_description")
    simulation_package = get_package_share_directory("diff_sim")
    rviz_file = os.path.join(simulation_package, "config", "rviz_config.rviz")
    gazebo_launch_file = os.path.join(get_package_share_directory("ros_gz_sim"), "launch", "gz_sim.launch.py")
    sdf_file = os.path.join(robot_description, "sdf", "my_diff_car_control_gz.sdf")
    controller_config_path = os.path.join(simulation_package, "config", "diff_drive_controller.yaml")
    robot_description_content = (
        open(sdf_file, "r").read().replace("PARAMETERS_CONFIG_FILE_PLACEHOLDER", controller_config_path)
    )
    robot_description = {"robot_description": robot_description_content}
    bridge_params = os.path.join(simulation_package, "config", "bridge_config_control_gz.yaml")
    joint_state_broadcaster_spawner = Node(
        package="controller_manager", executable="spawner", arguments=["joint_state_broadcaster"],
    )
    robot_controller_spawner = Node(
        package="controller_manager", executable="spawner",
        arguments=["diffbot_base_controller", "--param-file", controller_config_path],
    )
    robot_state_publisher_node = Node(
        package="robot_state_publisher", executable="robot_state_publisher", output="screen",
        parameters=[robot_description],
    )
    rviz_node = Node(
        package="rviz2", executable="rviz2", name="rviz2", output="screen", arguments=["-d", rviz_file],
        parameters=[{"use_sim_time": True}],
    )
    world = "empty.world"
    world_file = os.path.join(simulation_package, "worlds", world)
    gazebo_node = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(gazebo_launch_file),
        launch_arguments={"gz_args": [" -r -s -v4 ", world_file], "on_exit_shutdown": "true"}.items(),
    )
    gzclient_cmd = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(os.path.join(gazebo_launch_file)),
        launch_arguments={"gz_args": "-g -v4 "}.items(),
    )
    spawn_entity_node = Node(
        package="ros_gz_sim", executable="create", arguments=["-topic", "/robot_description", "-name", "robot"],
        output="screen",
    )
    start_gazebo_ros_bridge_cmd = Node(
        package="ros_gz_bridge", executable="parameter_bridge",
        arguments=["--ros-args", "-p", f"config_file:={bridge_params}"], output="screen",
    )
    delay_rviz_after_joint_state_broadcaster_spawner = RegisterEventHandler(
        event_handler=OnProcessExit(target_action=joint_state_broadcaster_spawner, on_exit=[rviz_node])
    )
    delay_joint_state_broadcaster_after_robot_controller_spawner = RegisterEventHandler(
        event_handler=OnProcessExit(target_action=robot_controller_spawner, on_exit=[joint_state_broadcaster_spawner])
    )
    return LaunchDescription([
        DeclareLaunchArgument("use_sim_time", default_value="true",
                              description="Use simulation (Gazebo) clock if true"),
        robot_state_publisher_node,
        robot_controller_spawner,
        gazebo_node,
        gzclient_cmd,
        spawn_entity_node,
        start_gazebo_ros_bridge_cmd,
        delay_joint_state_broadcaster_after_robot_controller_spawner,
        delay_rviz_after_joint_state_broadcaster_spawner,
    ])
'''


def tutorial_workspace(root: Path) -> Path:
    """~/ros2_ws as the tutorial builds it, with the project's robot and configuration files."""
    desc = write_tree(
        root / "src" / "robot_description",
        {
            "package.xml": package_xml("robot_description"),
            "CMakeLists.txt": "cmake_minimum_required(VERSION 3.8)\nproject(robot_description)\n"
            "find_package(ament_cmake REQUIRED)\ninstall(DIRECTORY sdf DESTINATION share/${PROJECT_NAME}/)\n"
            "ament_package()\n",
        },
    )
    (desc / "sdf").mkdir()
    shutil.copy(REPO / "description" / "my_diff_car_control.sdf", desc / "sdf" / "my_diff_car_control_gz.sdf")
    sim = write_tree(
        root / "src" / "diff_sim",
        {
            "package.xml": package_xml("diff_sim"),
            "CMakeLists.txt": "cmake_minimum_required(VERSION 3.8)\nproject(diff_sim)\n"
            "find_package(ament_cmake REQUIRED)\n"
            "install(DIRECTORY launch config worlds DESTINATION share/${PROJECT_NAME}/)\nament_package()\n",
            "launch/sim_control_gz.launch.py": TUTORIAL_LAUNCH,
        },
    )
    (sim / "config").mkdir()
    (sim / "worlds").mkdir()
    shutil.copy(REPO / "config" / "diff_drive_controller.yaml", sim / "config")
    shutil.copy(REPO / "config" / "bridge_config_control.yaml", sim / "config" / "bridge_config_control_gz.yaml")
    shutil.copy(REPO / "config" / "diffbot.rviz", sim / "config" / "rviz_config.rviz")
    shutil.copy(REPO / "config" / "worlds" / "empty.world", sim / "worlds")
    return root


def test_the_tutorials_launch_file_resolves_in_the_readers_workspace(tmp_path: Path, monkeypatch) -> None:
    ws = tutorial_workspace(tmp_path / "ros2_ws")
    monkeypatch.chdir(ws / "src" / "diff_sim")
    from diffctl.workspace.package_index import find_launch_file

    path = find_launch_file("diff_sim", "sim_control_gz.launch.py")
    run = started(path, exits=lambda name: False)  # every process keeps running: what the launch starts first
    world = run.one("gz_sim").argv[-1]
    assert Path(world).resolve() == ws / "src/diff_sim/worlds/empty.world"
    params = run.one("robot_state_publisher").params()
    controllers = Path(run.one("spawner").argv[-1])
    assert controllers.resolve() == ws / "src/diff_sim/config/diff_drive_controller.yaml"
    assert str(controllers) in params["robot_description"]  # the placeholder replaced with the share path
    assert "PARAMETERS_CONFIG_FILE_PLACEHOLDER" not in params["robot_description"]
    assert run.one("create").argv[-4:] == ["-topic", "/robot_description", "-name", "robot"]
    # the simulator is required: its exit alone shuts the launch down
    assert started(path, exits=lambda name: name == "gz_sim").required_exit


def test_the_same_from_the_command_line_from_anywhere(tmp_path: Path) -> None:
    ws = tutorial_workspace(tmp_path / "ros2_ws")
    r = subprocess.run(
        [sys.executable, "-m", "diffctl", "launch", "--workspace", str(ws), "diff_sim", "sim_control_gz.launch.py",
         "--print"],
        capture_output=True, text=True, timeout=120, cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    assert f"{ws}/src/diff_sim" not in r.stdout  # paths are the share tree's, as ROS gives install/ paths
    assert "diff_sim/share/diff_sim/config/rviz_config.rviz" in r.stdout
