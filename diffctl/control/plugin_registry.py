"""Controller and hardware plugins found through Python entry points (pluginlib's counterpart).

A package adds its own plugin by declaring, in its pyproject.toml,
    [project.entry-points."diffctl.controllers"]
    "my_pkg/MyController" = "my_pkg.controller:MyController"
(or the group "diffctl.hardware" for a hardware SystemInterface); diffctl needs no change.
`register_*` adds a class in-process (tests, notebooks).

A hardware plugin diffctl does not have is, almost always, the user's own C++ pluginlib plugin (the driver of
a real robot, `diffdrive_arduino/DiffDriveArduinoHardware`): that is bad input for diffctl, reported in one
line that names the plugin (and the `<ros2_control>` block and file when known) and says how to run the
same description on `mock_components/GenericSystem` instead.
"""

from __future__ import annotations

import importlib
from importlib.metadata import entry_points

from diffctl.control.controller_interface import ControllerInterface
from diffctl.control.hardware_interface import HardwareComponent, HardwareInfo
from diffctl.errors import ConfigError, suggest

CONTROLLER_GROUP = "diffctl.controllers"
HARDWARE_GROUP = "diffctl.hardware"

_local: dict[str, dict[str, type]] = {CONTROLLER_GROUP: {}, HARDWARE_GROUP: {}}


def register_controller(type_name: str, cls: type[ControllerInterface]) -> None:
    _local[CONTROLLER_GROUP][type_name] = cls


def register_hardware(plugin_name: str, cls: type[HardwareComponent]) -> None:
    _local[HARDWARE_GROUP][plugin_name] = cls


# The installed plugins by group, scanned once per process (pluginlib reads its manifests once too): a scan
# reads every installed distribution's metadata, 7 ms on a controller's load, so both groups are taken from
# one. A name not found triggers a rescan first, so a plugin installed while a manager runs is still found.
_scanned: dict[str, dict[str, str]] = {}


def _entry_points(group: str, *, rescan: bool = False) -> dict[str, str]:
    if rescan or group not in _scanned:
        every = entry_points()
        for name in (CONTROLLER_GROUP, HARDWARE_GROUP, group):
            _scanned[name] = {ep.name: ep.value for ep in every.select(group=name)}
    return _scanned[group]


def rescan() -> None:
    """Forget the scanned plugins (the manager's reload_controller_libraries)."""
    _scanned.clear()


def available(group: str) -> list[str]:
    return sorted(set(_entry_points(group)) | set(_local[group]))


def controller_types() -> list[str]:
    return available(CONTROLLER_GROUP)


def hardware_plugins() -> list[str]:
    return available(HARDWARE_GROUP)


MOCK_HARDWARE = "mock_components/GenericSystem"


def _unknown(group: str, name: str, what: str, source: str | None, block: str | None) -> ConfigError:
    close = suggest(name, available(group))
    if group != HARDWARE_GROUP or close:
        return ConfigError(
            f"unknown {what} plugin {name!r}{close}",
            source=source,
            hint="installed: " + (", ".join(available(group)) or "none"),
        )
    return ConfigError(
        f"hardware plugin {name!r} is not available in diffctl (a C++ ros2_control plugin can not be loaded; "
        f"diffctl has {', '.join(available(group)) or 'none'})",
        source=source,
        field=f"<ros2_control name={block!r}>/hardware/plugin" if block else None,
        hint=f"run it on mock hardware: use_mock_hardware:=true if your launch file or xacro has that argument, "
        f"or `diffctl control manager --hardware-plugin {MOCK_HARDWARE}`",
    )


def _load(group: str, name: str, base: type, what: str, source: str | None = None, block: str | None = None) -> type:
    if name in _local[group]:
        return _local[group][name]
    eps = _entry_points(group)
    if name not in eps:
        eps = _entry_points(group, rescan=True)
    if name not in eps:
        raise _unknown(group, name, what, source, block)
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


def hardware_class(plugin_name: str, source: str | None = None, block: str | None = None) -> type[HardwareComponent]:
    """The class of hardware plugin `plugin_name`; `source`/`block` (file, `<ros2_control name>`) locate errors."""
    return _load(HARDWARE_GROUP, plugin_name, HardwareComponent, "hardware", source, block)


def hardware_for(info: HardwareInfo) -> type[HardwareComponent]:
    """The plugin class of one `<ros2_control>` block (errors name the block and its file)."""
    return hardware_class(info.plugin_name, info.source, info.name)


def base_class_of(type_name: str) -> str:
    """The base class ros2 control reports in list_controller_types."""
    try:
        cls = controller_class(type_name)
    except ConfigError:
        return "controller_interface::ControllerInterface"
    if getattr(cls, "is_chainable", False):
        return "controller_interface::ChainableControllerInterface"
    return "controller_interface::ControllerInterface"
