"""The user's workspace: finding it, its packages, and their share directories, without colcon or CMake.

`share_dir(pkg)` is the one entry point the launch and description layers call for `$(find-pkg-share)`,
`FindPackageShare`, `get_package_share_directory` and xacro's `$(find)`. Precedence: the enclosing
workspace's sources (or `--workspace DIR` / $DIFFCTL_WORKSPACE), then the ROS packages diffctl replaces
(ros_gz_sim, …), then AMENT_PREFIX_PATH and COLCON_PREFIX_PATH install trees, then diffctl's demo
packages. This package imports no launch, bus, sim or control code.
"""

from __future__ import annotations

import os
from collections.abc import MutableMapping
from pathlib import Path

from diffctl.workspace.builtin import DEMO_DESCRIPTION_PACKAGE, DEMO_PACKAGE, project_root
from diffctl.workspace.discovery import WORKSPACE_ENV, find_workspace

TYPE_CHECKING = False  # typing unimported: `diffctl launch` reads this before its fork server's exec
if TYPE_CHECKING:
    from typing import Any

# The package index (resolve: package.xml, CMake install rules, lxml) is imported on first use: `diffctl launch`
# sets its children's environment with find_workspace and use_in_children before it starts the fork server,
# and every import in between delays the first component.
_RESOLVED = ("Package", "PackageNotFoundError", "find_package", "list_packages", "workspace_python_path")


def __getattr__(name: str) -> Any:
    if name in _RESOLVED:
        from diffctl.workspace import resolve

        return getattr(resolve, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "DEMO_DESCRIPTION_PACKAGE",
    "DEMO_PACKAGE",
    "PYTHON_PATH",
    "WORKSPACE_ENV",
    "Package",
    "PackageNotFoundError",
    "find_package",
    "find_workspace",
    "list_packages",
    "package_prefix",
    "project_root",
    "share_dir",
    "use_in_children",
    "workspace_python_path",
]

# The one overlay of ROS-named modules (ament_index_python, rclpy, launch, …), for child processes.
PYTHON_PATH = Path(__file__).resolve().parent.parent / "overlay"
# What sourcing /opt/ros/jazzy/setup.bash sets (ros_environment's hooks): launch files and nodes read them
# (`os.environ['ROS_DISTRO']`). A value already set (a sourced ROS 2, the user's own) is kept.
ROS_ENVIRONMENT = {"ROS_DISTRO": "jazzy", "ROS_VERSION": "2", "ROS_PYTHON_VERSION": "3"}


def share_dir(package: str) -> Path:
    """The share directory of `package` (ament_index's get_package_share_directory); raises
    PackageNotFoundError (exit 2) naming the places searched and close matches."""
    from diffctl.workspace.resolve import find_package

    return find_package(package).share


def package_prefix(package: str) -> Path:
    """The install prefix of `package` (ament_index's get_package_prefix): `<prefix>/share/<package>`
    is its share directory. diffctl's own packages are plain folders: their prefix is the folder itself."""
    from diffctl.workspace.resolve import find_package

    found = find_package(package)
    return found.prefix if found.prefix is not None else found.share


def use_in_children(workspace: Path | None, env: MutableMapping[str, str] = os.environ) -> None:
    """Make processes started with `env` resolve packages as this one does: the workspace in
    $DIFFCTL_WORKSPACE, diffctl's overlay on PYTHONPATH after any sourced ROS (xacro's `$(find)`, rclpy, …) and
    the workspace's Python packages after it (as colcon's site-packages would come), the workspace packages'
    environment hooks applied (GZ_SIM_RESOURCE_PATH …), as sourcing its setup.bash would, Jazzy's
    ROS_DISTRO / ROS_VERSION / ROS_PYTHON_VERSION unless set, and diffctl's `gz` (and `ros2`, without a real
    one) first on PATH."""
    from diffctl.cli.ros2 import put_ros2_on_path
    from diffctl.gz.path import put_gz_on_path

    put_gz_on_path(env)  # `ExecuteProcess(cmd=['gz', 'sim', …])` reaches diffctl's simulator
    put_ros2_on_path(env)  # `ExecuteProcess(cmd=['ros2', 'bag', 'record', …])` too, where ROS 2 is absent
    for name, value in ROS_ENVIRONMENT.items():
        env.setdefault(name, value)
    python: list[str] = []
    if workspace is not None:
        env[WORKSPACE_ENV] = str(workspace)
        from diffctl.workspace.env_hooks import apply_workspace_hooks
        from diffctl.workspace.resolve import workspace_python_path

        apply_workspace_hooks(env, workspace)
        python = [str(p) for p in workspace_python_path(workspace)]
    # The overlay goes after what PYTHONPATH already holds: a sourced ROS 2 installation (its rclpy, launch,
    # message packages) comes first and wins, as ARCHITECTURE.md promises; without one, the overlay answers.
    ours = {str(PYTHON_PATH), *python}
    parts = [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p and p not in ours]
    env["PYTHONPATH"] = os.pathsep.join([*parts, str(PYTHON_PATH), *python])
