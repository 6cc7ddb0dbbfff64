"""ament_index_python for processes diffctl starts (xacro run as a command, a workspace's Python nodes).

ROS's package is not on PyPI; this one answers from diffctl's resolution (the user's workspace, install
trees, diffctl's packages). The launcher puts its folder first on PYTHONPATH for its children.
"""

from ament_index_python.packages import (
    PackageNotFoundError,
    get_package_prefix,
    get_package_share_directory,
    get_package_share_path,
    get_packages_with_prefixes,
)

__all__ = [
    "PackageNotFoundError",
    "get_package_prefix",
    "get_package_share_directory",
    "get_package_share_path",
    "get_packages_with_prefixes",
]
