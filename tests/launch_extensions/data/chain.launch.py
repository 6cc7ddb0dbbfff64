"""chain.yaml with the Python frontend: launch's own classes, and diffctl's WaitFor for readiness."""

from launch.actions import DeclareLaunchArgument, ExecuteProcess, RegisterEventHandler
from launch.event_handlers import OnProcessExit, OnProcessStart
from launch.substitutions import LaunchConfiguration

from diffctl.launch_extensions import WaitFor
from launch import LaunchDescription


def generate_launch_description():
    run = [LaunchConfiguration("python"), LaunchConfiguration("step"), LaunchConfiguration("record")]

    def step(name, *args):
        return ExecuteProcess(name=name, cmd=[*run, name, *args])

    sim = step("sim", "--print", "world ready", "--sleep", "0.6")
    spawn_entity = step("spawn_entity", "--sleep", "0.2")
    base_spawner = step("base_spawner")
    jsb_spawner = step("jsb_spawner", "--sleep", "0.2")
    viz = step("viz")
    return LaunchDescription(
        [
            DeclareLaunchArgument("python"),
            DeclareLaunchArgument("step"),
            DeclareLaunchArgument("record"),
            sim,
            WaitFor([WaitFor.log(sim, "world .*")], actions=[spawn_entity]),
            WaitFor([WaitFor.exited(spawn_entity)], actions=[base_spawner], timeout=20.0),
            RegisterEventHandler(OnProcessExit(target_action=base_spawner, on_exit=[jsb_spawner])),
            RegisterEventHandler(
                OnProcessExit(
                    target_action=jsb_spawner,
                    on_exit=lambda event, context: [viz] if event.returncode == 0 else [step("never")],
                )
            ),
            RegisterEventHandler(OnProcessStart(target_action=viz, on_start=[step("viz_up")])),
        ]
    )
