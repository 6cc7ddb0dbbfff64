"""ros_gz_sim's gz_sim.launch.py for diffctl: `gz_args` go to `diffctl sim run`, as they would go to `gz sim`.

Included by launch files written for Gazebo, e.g. the tutorial's
`IncludeLaunchDescription(PythonLaunchDescriptionSource(.../gz_sim.launch.py), launch_arguments={"gz_args": …})`.
`gz sim -g` alone (the GUI client) starts nothing: diffctl's simulator is headless and the browser
visualizer (rviz2) shows the scene.
"""

from diffctl.launch import (
    DeclareLaunchArgument,
    IfCondition,
    LaunchConfiguration,
    LaunchDescription,
    LogInfo,
    Node,
    PythonExpression,
    Shutdown,
)
from diffctl.launch.process_actions import SplitArgs


def generate_launch_description():
    gz_args = LaunchConfiguration("gz_args")
    words = ["'''", gz_args, "'''.split()"]
    gui_only = PythonExpression(["'-g' in ", *words])
    shutdown_on_exit = PythonExpression(
        ["'-g' not in ", *words, " and '''", LaunchConfiguration("on_exit_shutdown"), "'''.lower() in ('true', '1')"]
    )
    keep_running = PythonExpression(
        [
            "'-g' not in ",
            *words,
            " and '''",
            LaunchConfiguration("on_exit_shutdown"),
            "'''.lower() not in ('true', '1')",
        ]
    )

    def server(**kw):
        return Node(package="ros_gz_sim", executable="gz_sim", arguments=[SplitArgs(gz_args)], output="screen", **kw)

    return LaunchDescription(
        [
            DeclareLaunchArgument("gz_args", default_value="", description="Arguments for the simulator (gz sim)"),
            DeclareLaunchArgument("gz_version", default_value="8", description="Accepted for compatibility"),
            DeclareLaunchArgument(
                "on_exit_shutdown", default_value="false", description="Shut the launch down when the simulator exits"
            ),
            LogInfo(
                msg="gz sim -g (GUI client): diffctl's simulator is headless; the browser visualizer shows the scene",
                condition=IfCondition(gui_only),
            ),
            server(on_exit=Shutdown(), condition=IfCondition(shutdown_on_exit)),
            server(condition=IfCondition(keep_running)),
        ]
    )
