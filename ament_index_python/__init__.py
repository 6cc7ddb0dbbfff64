"""ament_index_python's API answered by diffctl's package index, for tools diffctl runs without a ROS install.

xacro's `$(find pkg)` imports `ament_index_python.packages` when it runs as the `xacro` command (e.g. from a
launch file's `Command([FindExecutable(name='xacro'), …])`); this package makes that import resolve through
`diffctl.workspace` (the user's workspace, then AMENT_PREFIX_PATH install trees, then diffctl's packages).
A sourced ROS installation comes first on PYTHONPATH and wins, as it should.
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
