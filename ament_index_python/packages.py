"""`get_package_share_directory` and friends over diffctl's package index (same names and errors as ROS's)."""

from __future__ import annotations

import re
from pathlib import Path

_VALID_NAME = re.compile(r"^[a-zA-Z0-9][a-zA-Z0-9_-]+$")  # ament_index_python's resource-name rule


class PackageNotFoundError(KeyError):
    """Raised when a package is not found (a KeyError, as in ament_index_python)."""


def _lookup(package_name: str) -> tuple[Path, Path]:
    if not _VALID_NAME.match(package_name):
        raise ValueError(f"'{package_name}' is not a valid package name")
    from diffctl.errors import DiffctlError
    from diffctl.workspace import package_prefix, share_dir

    try:
        return package_prefix(package_name), share_dir(package_name)
    except DiffctlError as e:
        raise PackageNotFoundError(e.message) from None


def get_package_prefix(package_name: str) -> str:
    return str(_lookup(package_name)[0])


def get_package_share_directory(package_name: str, print_warning: bool = True) -> str:
    return str(_lookup(package_name)[1])


def get_package_share_path(package_name: str, print_warning: bool = True) -> Path:
    return _lookup(package_name)[1]


def get_packages_with_prefixes() -> dict[str, str]:
    from diffctl.workspace import list_packages

    return {p.name: str(p.prefix if p.prefix is not None else p.share.parent) for p in list_packages()}
