"""`diffctl robot-localization ekf_node|ukf_node|navsat_transform_node`: the executables of package
robot_localization (`Node(package='robot_localization', executable='ekf_node', parameters=[…])`,
`diffctl run robot_localization ekf_node --ros-args --params-file ekf.yaml`)."""

from __future__ import annotations

import click

_PASS_THROUGH = {"ignore_unknown_options": True, "allow_interspersed_args": False}


@click.group("robot-localization")
def robot_localization() -> None:
    """robot_localization's nodes: EKF and UKF state estimation, GPS (navsat) transform.

    \b
    Example:
      diffctl robot-localization ekf_node --ros-args --params-file config/ekf.yaml
      diffctl run robot_localization navsat_transform_node --ros-args -p use_odometry_yaw:=true
    """


@robot_localization.command("ekf_node", context_settings=_PASS_THROUGH)
def ekf_node() -> None:
    """Extended Kalman filter: fuses odomN/poseN/twistN/imuN into odometry/filtered and TF."""
    from diffctl.robot_localization.filter_node import run

    raise SystemExit(run("ekf"))


@robot_localization.command("ukf_node", context_settings=_PASS_THROUGH)
def ukf_node() -> None:
    """Unscented Kalman filter (alpha, kappa, beta): the same parameters, topics and services as ekf_node."""
    from diffctl.robot_localization.filter_node import run

    raise SystemExit(run("ukf"))


@robot_localization.command("navsat_transform_node", context_settings=_PASS_THROUGH)
def navsat_transform_node() -> None:
    """GPS fixes (gps/fix) into the robot's world frame (odometry/gps), and back (gps/filtered)."""
    from diffctl.robot_localization.navsat_node import run

    raise SystemExit(run())
