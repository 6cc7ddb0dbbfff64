"""ament_index_python.packages' functions answered by diffctl's resolution (same names, same errors).

Both `ament_index_python` shims import from here: the one installed beside diffctl (for `xacro` run from the
venv) and the one the launcher puts first on its children's PYTHONPATH (so it wins over a sourced ROS, whose
index does not know the user's unbuilt source packages). A package that only the resource index on
AMENT_PREFIX_PATH lists (its share folder missing) is still answered, with ament's warning, as ament does.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path

from diffctl.workspace import PackageNotFoundError, find_package, list_packages, package_prefix, resource_index

__all__ = [
    "PackageNotFoundError",
    "get_package_prefix",
    "get_package_share_directory",
    "get_package_share_path",
    "get_packages_with_prefixes",
]

_VALID_NAME = re.compile(r"[a-zA-Z0-9][a-zA-Z0-9_-]+", re.ASCII)  # REP 127 with its recommended exemptions


def _checked(package_name: str) -> str:
    if _VALID_NAME.fullmatch(package_name) is None:
        raise ValueError(f"'{package_name}' is not a valid package name")
    return package_name


def _indexed_prefix(package_name: str) -> str | None:
    try:
        found = resource_index.has_resource("packages", package_name)
    except OSError:  # AMENT_PREFIX_PATH unset: diffctl's own resolution has answered already
        return None
    return found or None


def get_package_prefix(package_name: str) -> str:
    try:
        return str(package_prefix(_checked(package_name)))
    except PackageNotFoundError:
        prefix = _indexed_prefix(package_name)
        if prefix is None:
            raise
        return prefix


def _share(package_name: str) -> Path:
    try:
        return find_package(_checked(package_name)).share
    except PackageNotFoundError:
        prefix = _indexed_prefix(package_name)
        if prefix is None:
            raise
        return Path(prefix, "share", package_name)


def get_package_share_directory(package_name: str, print_warning: bool = True) -> str:
    share = _share(package_name)
    if print_warning and not share.exists():
        warnings.warn(f"Share directory for {package_name} ({share}) does not exist.", stacklevel=2)
    return str(share)


def get_package_share_path(package_name: str, print_warning: bool = True) -> Path:
    share = _share(package_name)
    if print_warning and not share.exists():
        warnings.warn(f"Share path for {package_name} ({share}) does not exist.", stacklevel=2)
    return share


def get_packages_with_prefixes() -> dict[str, str]:
    found = {p.name: str(p.prefix if p.prefix is not None else p.share) for p in list_packages()}
    try:
        indexed = resource_index.get_resources("packages")
    except OSError:
        indexed = {}
    for name, prefix in indexed.items():
        found.setdefault(name, prefix)
    return found
