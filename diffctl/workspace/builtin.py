"""diffctl's own packages: the demo packages and the share folders of the ROS packages diffctl replaces.

The demo packages carry `diffctl_demo` names so a user's `robot_description` or `diff_sim` package can
never be shadowed by them: `diffctl_demo` is the top of the project (its launch/, config/, description/),
`diffctl_demo_description` its description/ folder — from a checkout, or from diffctl/share in a wheel.
"""

from __future__ import annotations

import os
from pathlib import Path

DEMO_PACKAGE = "diffctl_demo"
DEMO_DESCRIPTION_PACKAGE = "diffctl_demo_description"
PROJECT_DIR_ENV = "DIFFCTL_PROJECT_DIR"

_PACKAGE_DIR = Path(__file__).resolve().parent.parent
# Share folders of replaced ROS packages (e.g. ros_gz_sim/launch/gz_sim.launch.py), one folder each.
COMPONENT_SHARES = _PACKAGE_DIR / "workspace" / "component_shares"
# An ament prefix (share/<pkg>, the resource index) of the ROS library packages diffctl reimplements in Python
# (launch_ros, …): found after install trees, as a sourced ROS's own copy of the library is what Python imports.
LIBRARY_PREFIX = _PACKAGE_DIR / "workspace" / "library_prefix"
# Gazebo's own worlds (empty.sdf, …): where `gz sim NAME` looks after GZ_SIM_RESOURCE_PATH.
GAZEBO_WORLDS = COMPONENT_SHARES / "ros_gz_sim" / "worlds"


def project_root() -> Path:
    """The top of the project: the checkout holding diffctl/, or diffctl/share in an installed wheel."""
    override = os.environ.get(PROJECT_DIR_ENV)
    if override:
        return Path(override).resolve()
    top = _PACKAGE_DIR.parent
    if (top / "pyproject.toml").is_file() and (top / "launch").is_dir():
        return top
    return _PACKAGE_DIR / "share"


def demo_packages() -> dict[str, Path]:
    root = project_root()
    return {DEMO_PACKAGE: root, DEMO_DESCRIPTION_PACKAGE: root / "description"}


def replacement_packages() -> dict[str, Path]:
    """Share folders of the ROS packages diffctl replaces (ros_gz_sim, …)."""
    if not COMPONENT_SHARES.is_dir():
        return {}
    return {p.name: p for p in sorted(COMPONENT_SHARES.iterdir()) if p.is_dir() and not p.name.startswith(("_", "."))}


def builtin_packages() -> dict[str, Path]:
    """Package name → share directory of every package diffctl ships."""
    return {**demo_packages(), **replacement_packages()}
