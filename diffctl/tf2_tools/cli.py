"""`diffctl tf2 static_transform_publisher …` / `diffctl tf2 tf2_echo …`: the executables of package tf2_ros
(`Node(package='tf2_ros', executable='static_transform_publisher', arguments=[…])` in a launch file,
`diffctl run tf2_ros tf2_echo a b`). Their arguments are the C++ programs' own, passed through untouched."""

from __future__ import annotations

import click

_PASS_THROUGH = {"ignore_unknown_options": True, "allow_interspersed_args": False, "help_option_names": []}


@click.group("tf2")
def tf2() -> None:
    """tf2_ros's tools: static_transform_publisher and tf2_echo.

    \b
    Example:
      diffctl tf2 static_transform_publisher --x 1 --yaw 1.57 --frame-id base_link --child-frame-id laser
      diffctl tf2 tf2_echo odom base_footprint
    """


@tf2.command("static_transform_publisher", context_settings=_PASS_THROUGH, add_help_option=False)
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def static_transform_publisher(args: tuple[str, ...]) -> None:
    """Publish one static transform on /tf_static (--help: the program's usage); also the old positional
    forms `x y z yaw pitch roll frame child` and `x y z qx qy qz qw frame child`, deprecated as in ROS."""
    from diffctl.tf2_tools.programs import static_transform_publisher as run

    raise SystemExit(run(list(args)))


@tf2.command("tf2_echo", context_settings=_PASS_THROUGH, add_help_option=False)
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def tf2_echo(args: tuple[str, ...]) -> None:
    """Print the transform from SOURCE_FRAME to TARGET_FRAME at ECHO_RATE Hz (1): tf2_echo source target [rate]."""
    from diffctl.tf2_tools.programs import tf2_echo as run

    raise SystemExit(run(list(args)))
