"""Real ROS 2 programs in diffctl's graph, and what to do about a package diffctl does not provide.

A package diffctl does not provide (Nav2, slam_toolbox, a driver) runs as itself when a sourced ROS 2 install
(AMENT_PREFIX_PATH, COLCON_PREFIX_PATH) or the user's built workspace has it: its program joins diffctl's
graph over rmw_zenoh, as any ROS 2 node joins a Zenoh router — RMW_IMPLEMENTATION=rmw_zenoh_cpp and, through
rmw_zenoh's ZENOH_CONFIG_OVERRIDE, a connection to diffctl's router (DIFFCTL_ROUTER). Where no install has it,
the one error names the package and the way to get it.
"""

from __future__ import annotations

import os
from pathlib import Path

from diffctl.workspace import prefixes

RMW_ZENOH = "rmw_zenoh_cpp"
# diffctl's router endpoint when DIFFCTL_ROUTER is unset (diffctl.bus.session's default; workspace sits below
# bus in the layers, so the value is repeated here rather than imported).
DEFAULT_ROUTER = "tcp/127.0.0.1:7447"

# Packages launch files start that diffctl deliberately leaves to ROS 2: too big to provide faithfully here, or
# drivers of real hardware. Name → what the user installs (besides the generic ros-jazzy-<name>).
LEFT_TO_ROS: dict[str, str] = {
    "nav2_bringup": "Nav2 (ros-jazzy-navigation2 ros-jazzy-nav2-bringup)",
    "slam_toolbox": "slam_toolbox (ros-jazzy-slam-toolbox)",
    "cartographer_ros": "Cartographer (ros-jazzy-cartographer-ros)",
    "moveit_ros_move_group": "MoveIt 2 (ros-jazzy-moveit)",
    "micro_ros_agent": "the micro-ROS agent (built from micro_ros_setup)",
}
# Names older launch files use for packages diffctl provides under their current names.
RENAMED = {
    "ros_ign_gazebo": "ros_gz_sim",
    "ros_ign_bridge": "ros_gz_bridge",
    "ros_ign_image": "ros_gz_image",
    "ros_ign": "ros_gz",
    "ign_ros2_control": "gz_ros2_control",
    "rviz": "rviz2",  # ROS 1's: Jazzy has no ros-jazzy-rviz to install
}


def apt_name(package: str) -> str:
    return "ros-jazzy-" + package.replace("_", "-")


def _install_what(package: str) -> str:
    if package.startswith(("nav2_", "opennav_")):
        return LEFT_TO_ROS["nav2_bringup"]
    if package.startswith("moveit"):
        return LEFT_TO_ROS["moveit_ros_move_group"]
    return LEFT_TO_ROS.get(package, apt_name(package))


def how_to_get(package: str) -> str:
    """One sentence: how a user gets `package` that diffctl does not provide."""
    if package in RENAMED:
        return f"{package} is the old name of {RENAMED[package]}, which diffctl provides: use that name"
    what = _install_what(package)
    return (
        f"diffctl does not provide it: install {what} and `source /opt/ros/jazzy/setup.bash` (diffctl then starts "
        f"the real one, joined to its graph over rmw_zenoh: install {apt_name(RMW_ZENOH)} too), or put its "
        "sources in your workspace's src/"
    )


def missing_module_hint(module: str) -> str:
    """What to do about a Python module a launch file imports that neither diffctl, its venv nor the workspace
    has: a ROS 2 package's comes with its install or its sources, anything else from pip."""
    top = module.split(".")[0]
    return (
        f"diffctl does not provide the Python package {top!r}: if it is a ROS 2 package, install "
        f"{_install_what(top)} and `source /opt/ros/jazzy/setup.bash`, or put its sources in your workspace's "
        f"src/; if it comes from PyPI, pip install it into diffctl's Python environment"
    )


def has_rmw_zenoh() -> bool:
    """Whether an install on AMENT_PREFIX_PATH / COLCON_PREFIX_PATH holds rmw_zenoh_cpp."""
    return any((p.path / prefixes.MARKERS / RMW_ZENOH).is_file() for p in prefixes.install_prefixes())


def zenoh_override(env: dict[str, str] | os._Environ[str]) -> str:
    """rmw_zenoh's ZENOH_CONFIG_OVERRIDE that connects a session to diffctl's router, keeping the user's own
    overrides (theirs win where they name the same key)."""
    endpoint = env.get("DIFFCTL_ROUTER") or DEFAULT_ROUTER
    mine = f'connect/endpoints=["{endpoint}"]'
    theirs = (env.get("ZENOH_CONFIG_OVERRIDE") or "").strip().strip(";")
    if not theirs:
        return mine
    if any(item.split("=", 1)[0].strip() == "connect/endpoints" for item in theirs.split(";")):
        return theirs
    return f"{mine};{theirs}"


def real_program_argv(program: Path, env: dict[str, str] | os._Environ[str] = os.environ) -> list[str]:
    """The command that starts a real ROS 2 program in diffctl's graph: `env` sets rmw_zenoh's variables and
    execs the program, so the launcher watches, signals and reaps the program itself."""
    rmw = env.get("RMW_IMPLEMENTATION") or RMW_ZENOH
    return ["env", f"RMW_IMPLEMENTATION={rmw}", f"ZENOH_CONFIG_OVERRIDE={zenoh_override(env)}", str(program)]
