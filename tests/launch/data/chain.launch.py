"""chain.yaml written with the Python frontend, as a ROS 2 user would."""

from launch.actions import DeclareLaunchArgument, ExecuteProcess, LogInfo, RegisterEventHandler
from launch.event_handlers import OnProcessExit, OnProcessStart
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution, ThisLaunchFileDir

from diffctl.launch_legacy import WaitFor
from launch import LaunchDescription


def generate_launch_description():
    python = LaunchConfiguration("python")
    step = [python, PathJoinSubstitution([ThisLaunchFileDir(), "step.py"]), LaunchConfiguration("record")]
    sim = ExecuteProcess(name="sim", cmd=[*step, "sim", "--print", "world ready", "--sleep", "0.6"])
    spawn_entity = ExecuteProcess(
        name="spawn_entity", cmd=[*step, "spawn_entity", "--sleep", "0.2"], wait_for=[WaitFor.log(sim, "world ready")]
    )
    base_spawner = ExecuteProcess(
        name="base_spawner", cmd=[*step, "base_spawner"], wait_for=[WaitFor.exited(spawn_entity)]
    )
    jsb_spawner = ExecuteProcess(name="jsb_spawner", cmd=[*step, "jsb_spawner", "--sleep", "0.2"])
    viz = ExecuteProcess(name="viz", cmd=[*step, "viz"])
    return LaunchDescription(
        [
            DeclareLaunchArgument("python", default_value="python3", description="interpreter for step.py"),
            DeclareLaunchArgument("record", description="file each process appends its name to"),
            sim,
            spawn_entity,
            base_spawner,
            RegisterEventHandler(OnProcessExit(target_action=base_spawner, on_exit=[jsb_spawner])),
            RegisterEventHandler(OnProcessExit(target_action=jsb_spawner, on_exit=[viz], exit_code=0)),
            RegisterEventHandler(OnProcessStart(target_action=viz, on_start=[LogInfo(msg="viz is up")])),
        ]
    )
