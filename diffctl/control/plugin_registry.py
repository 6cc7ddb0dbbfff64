"""Controller and hardware plugins found through Python entry points (pluginlib's counterpart).

A package adds its own plugin by declaring, in its pyproject.toml,
    [project.entry-points."diffctl.controllers"]
    "my_pkg/MyController" = "my_pkg.controller:MyController"
(or the group "diffctl.hardware" for a hardware SystemInterface); diffctl needs no change.
`register_*` adds a class in-process (tests, notebooks).
"""

from __future__ import annotations

import importlib
from importlib.metadata import entry_points

from diffctl.control.controller_interface import ControllerInterface
from diffctl.control.hardware_interface import HardwareComponent
from diffctl.errors import ConfigError, suggest

CONTROLLER_GROUP = "diffctl.controllers"
HARDWARE_GROUP = "diffctl.hardware"

_local: dict[str, dict[str, type]] = {CONTROLLER_GROUP: {}, HARDWARE_GROUP: {}}


def register_controller(type_name: str, cls: type[ControllerInterface]) -> None:
    _local[CONTROLLER_GROUP][type_name] = cls


def register_hardware(plugin_name: str, cls: type[HardwareComponent]) -> None:
    _local[HARDWARE_GROUP][plugin_name] = cls


def _entry_points(group: str) -> dict[str, str]:
    return {ep.name: ep.value for ep in entry_points(group=group)}


def available(group: str) -> list[str]:
    return sorted(set(_entry_points(group)) | set(_local[group]))


def controller_types() -> list[str]:
    return available(CONTROLLER_GROUP)


def hardware_plugins() -> list[str]:
    return available(HARDWARE_GROUP)


def _load(group: str, name: str, base: type, what: str) -> type:
    if name in _local[group]:
        return _local[group][name]
    eps = _entry_points(group)
    if name not in eps:
        raise ConfigError(
            f"unknown {what} plugin {name!r}{suggest(name, available(group))}",
            hint="installed: " + (", ".join(available(group)) or "none"),
        )
    module_name, _, attr = eps[name].partition(":")
    try:
        obj = importlib.import_module(module_name)
        for part in attr.split("."):
            obj = getattr(obj, part)
    except (ImportError, AttributeError) as e:
        raise ConfigError(f"{what} plugin {name!r} ({eps[name]}) cannot be loaded: {e}") from None
    if not (isinstance(obj, type) and issubclass(obj, base)):
        raise ConfigError(f"{what} plugin {name!r} ({eps[name]}) is not a {base.__name__} subclass")
    return obj


def controller_class(type_name: str) -> type[ControllerInterface]:
    return _load(CONTROLLER_GROUP, type_name, ControllerInterface, "controller")


def hardware_class(plugin_name: str) -> type[HardwareComponent]:
    return _load(HARDWARE_GROUP, plugin_name, HardwareComponent, "hardware")


def base_class_of(type_name: str) -> str:
    """The base class ros2 control reports in list_controller_types."""
    try:
        cls = controller_class(type_name)
    except ConfigError:
        return "controller_interface::ControllerInterface"
    if getattr(cls, "is_chainable", False):
        return "controller_interface::ChainableControllerInterface"
    return "controller_interface::ControllerInterface"
