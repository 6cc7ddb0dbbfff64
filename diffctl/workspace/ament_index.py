"""ament_index_python.packages' functions answered by diffctl's resolution (same names, same errors).

Both `ament_index_python` shims import from here: the one installed beside diffctl (for `xacro` run from the
venv) and the one the launcher puts first on its children's PYTHONPATH (so it wins over a sourced ROS, whose
index does not know the user's unbuilt source packages).
"""

from __future__ import annotations

import re
from pathlib import Path

from diffctl.workspace import PackageNotFoundError, find_package, list_packages, package_prefix

__all__ = [
    "PackageNotFoundError",
    "get_package_prefix",
    "get_package_share_directory",
    "get_package_share_path",
    "get_packages_with_prefixes",
]

_VALID_NAME = re.compile(r"^[a-zA-Z0-9][a-zA-Z0-9_-]+$")  # ament_index_python's resource-name rule


def _checked(package_name: str) -> str:
    if not _VALID_NAME.match(package_name):
        raise ValueError(f"'{package_name}' is not a valid package name")
    return package_name


def get_package_prefix(package_name: str) -> str:
    return str(package_prefix(_checked(package_name)))


def get_package_share_directory(package_name: str, print_warning: bool = True) -> str:
    return str(find_package(_checked(package_name)).share)


def get_package_share_path(package_name: str, print_warning: bool = True) -> Path:
    return find_package(_checked(package_name)).share


def get_packages_with_prefixes() -> dict[str, str]:
    return {p.name: str(p.prefix if p.prefix is not None else p.share) for p in list_packages()}
