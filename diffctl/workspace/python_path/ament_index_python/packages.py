"""ament_index_python.packages answered by diffctl.workspace (same names and errors as ROS's module)."""

from pathlib import Path

from diffctl.workspace import PackageNotFoundError, find_package, list_packages, package_prefix

__all__ = [
    "PackageNotFoundError",
    "get_package_prefix",
    "get_package_share_directory",
    "get_package_share_path",
    "get_packages_with_prefixes",
]


def get_package_prefix(package_name: str) -> str:
    return str(package_prefix(package_name))


def get_package_share_directory(package_name: str, print_warning: bool = True) -> str:
    return str(find_package(package_name).share)


def get_package_share_path(package_name: str, print_warning: bool = True) -> Path:
    return find_package(package_name).share


def get_packages_with_prefixes() -> dict[str, str]:
    return {p.name: str(p.prefix if p.prefix is not None else p.share) for p in list_packages()}
