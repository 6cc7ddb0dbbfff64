"""Which interface packages and interfaces exist (rosidl_runtime_py.get_interfaces): diffctl's registry in
place of the ament index's `rosidl_interfaces` resources — the workspace's, install trees' and diffctl's."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from diffctl.interfaces import registry

_EXT = {"msg": ".msg", "srv": ".srv", "action": ".action"}


def get_interface_packages() -> dict[str, str]:
    """Package → where it is defined (its folder, or 'diffctl')."""
    out = {}
    for name in registry.all_package_names():
        p = registry.package(name)
        if p is not None:
            out[name] = p.where
    return out


def _is_package(name: str) -> bool:
    """A package that exists but defines no interfaces: one diffctl resolves (workspace, install trees, its
    own) or a ROS Python package its overlay provides (rclpy, rosidl_parser, tf2_ros, …)."""
    from diffctl.errors import DiffctlError
    from diffctl.workspace import PYTHON_PATH, find_package

    if (PYTHON_PATH / name / "__init__.py").is_file():
        return True
    try:
        find_package(name)
    except DiffctlError:  # not found, or not a valid package name
        return False
    return True


def _interfaces(package_names: Iterable[str]) -> dict[str, dict[str, list[str]]]:
    names = list(package_names) or registry.all_package_names()
    out = {}
    for name in names:
        p = registry.package(name)
        if p is not None:
            out[name] = p.interfaces
        elif not _is_package(name):
            raise LookupError(f"Unknown package '{name}'")
    return out


def _select(package_names: Iterable[str], kinds: tuple[str, ...]) -> dict[str, list[str]]:
    out = {}
    for pkg, interfaces in _interfaces(package_names).items():
        found = sorted(f"{k}/{n}" for k in kinds for n in interfaces.get(k, []) if "_" not in n)
        if found:
            out[pkg] = found
    return out


def get_interfaces(package_names: Iterable[str] = ()) -> dict[str, list[str]]:
    return _select(package_names, ("msg", "srv", "action"))


def get_message_interfaces(package_names: Iterable[str] = ()) -> dict[str, list[str]]:
    return _select(package_names, ("msg",))


def get_service_interfaces(package_names: Iterable[str] = ()) -> dict[str, list[str]]:
    return _select(package_names, ("srv",))


def get_action_interfaces(package_names: Iterable[str] = ()) -> dict[str, list[str]]:
    return _select(package_names, ("action",))


def get_interface_path(interface_name: str) -> str:
    """The definition file of `pkg/kind/Name[.ext]`; LookupError where diffctl has the type but no file
    (a type of rosbags' store)."""
    parts = interface_name.split("/")
    if len(parts) < 2:
        raise ValueError(f"Invalid name '{interface_name}'. Expected at least two parts separated by '/'")
    if not all(parts):
        raise ValueError(f"Invalid name '{interface_name}'. Must not contain empty parts")
    if ".." in parts:
        raise ValueError(f"Invalid name '{interface_name}'. Must not contain '..'")
    p = registry.package(parts[0])
    if p is None:
        raise LookupError(f"Unknown package '{parts[0]}'")
    stem, dot, _ = parts[-1].partition(".")
    path = p.files.get("/".join([*parts[:-1], stem]))
    if path is not None and dot:
        # a suffix asks for that very file (`.idl` beside the `.msg`, as rosidl_adapter installs it)
        path = Path(path).with_name(parts[-1])
    if path is None or not Path(path).exists():
        raise LookupError(f"Could not find the interface '{interface_name}'")
    return str(path)
