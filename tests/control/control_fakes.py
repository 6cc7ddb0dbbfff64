"""A test controller plugin, a recording logger and hardware info builders for manager unit tests (the
controllers' nodes are real client nodes: `client_bus` must be active)."""

from __future__ import annotations

import math
from typing import Any

from diffctl.control.controller_interface import ControllerInterface, InterfaceConfiguration, ReturnType
from diffctl.control.controllers.param_decl import overrides
from diffctl.control.hardware_interface import ComponentInfo, HardwareInfo, InterfaceInfo
from diffctl.control.manager import ControllerManager
from diffctl.control.params import manager_params
from diffctl.control.plugin_registry import register_controller
from tests.control.controllers.controller_harness import make_node


class RecordingLog:
    """The manager's logger, recorded (it takes any object with debug/info/warn/error)."""

    def __init__(self) -> None:
        self.lines: list[tuple[str, str]] = []

    def debug(self, text: str, **_kw: Any) -> None:
        self.lines.append(("DEBUG", text))

    def info(self, text: str, **_kw: Any) -> None:
        self.lines.append(("INFO", text))

    def warn(self, text: str, **_kw: Any) -> None:
        self.lines.append(("WARN", text))

    def error(self, text: str, **_kw: Any) -> None:
        self.lines.append(("ERROR", text))

    def text(self, level: str | None = None) -> str:
        return "\n".join(t for lv, t in self.lines if level is None or lv == level)


class FakeController(ControllerInterface):
    """Claims the command/state interfaces named in its params; behaviour switches come from params too."""

    def __init__(self) -> None:
        super().__init__()
        self.calls: list[str] = []
        self.updates: list[tuple[int, float]] = []
        self.result = ReturnType.OK
        self.raise_in: set[str] = set()

    def _hook(self, name: str) -> None:
        self.calls.append(name)
        if name in self.raise_in:
            raise RuntimeError(f"{name} exploded")

    def on_init(self) -> None:
        self.params = overrides(self.get_node())  # its behaviour, from its node's overrides
        self.raise_in = set(self.params.get("raise_in", []))
        self._hook("on_init")

    def command_interface_configuration(self) -> InterfaceConfiguration:
        cmds = self.params.get("commands")
        return InterfaceConfiguration.all() if cmds == "all" else InterfaceConfiguration.individual(cmds or [])

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual(self.params.get("states", []))

    def on_configure(self, previous_state: Any) -> None:
        self._hook("on_configure")

    def on_activate(self, previous_state: Any) -> None:
        self._hook("on_activate")

    def on_deactivate(self, previous_state: Any) -> None:
        self._hook("on_deactivate")
        for c in self.command_interfaces:
            c.set_value(0.0)

    def on_cleanup(self, previous_state: Any) -> None:
        self._hook("on_cleanup")

    def on_shutdown(self, previous_state: Any) -> None:
        self._hook("on_shutdown")

    def update(self, time: Any, period: Any) -> ReturnType:
        self.updates.append((time.nanoseconds, period.nanoseconds * 1e-9))
        if "update" in self.raise_in:
            raise ValueError("update exploded")
        for c in self.command_interfaces:
            c.set_value(float(self.params.get("command_value", 1.0)))
        return self.result


register_controller("test_controllers/Fake", FakeController)

WHEELS = ("left_wheel", "right_wheel")


def wheel_info(
    name: str = "robot",
    plugin: str = "mock_components/GenericSystem",
    joints: tuple[str, ...] = WHEELS,
    commands: tuple[str, ...] = ("velocity",),
    hw_params: dict[str, str] | None = None,
    initial_position: float | None = None,
) -> HardwareInfo:
    return HardwareInfo(
        name=name,
        plugin_name=plugin,
        hardware_parameters=dict(hw_params or {}),
        joints=tuple(
            ComponentInfo(
                j,
                command_interfaces=tuple(InterfaceInfo(c) for c in commands),
                state_interfaces=(InterfaceInfo("position", initial_value=initial_position), InterfaceInfo("velocity")),
            )
            for j in joints
        ),
    )


def make_manager(
    controllers: dict[str, dict[str, Any]] | None = None,
    *,
    update_rate: int = 100,
    hardware: list[HardwareInfo] | None = None,
    robot_description: str = "",
    **flat: Any,
) -> tuple[ControllerManager, RecordingLog]:
    """A manager with mock hardware and fake controllers `{name: params}` registered as test_controllers/Fake."""
    params: dict[str, Any] = {"update_rate": update_rate, **flat}
    ctrl_params = controllers or {}
    for name in ctrl_params:
        params[f"{name}.type"] = "test_controllers/Fake"
    log = RecordingLog()
    nodes: dict[str, Any] = {}

    def factory(name: str, _arguments: list[str]) -> Any:
        nodes[name] = make_node(name, ctrl_params.get(name, {}))
        return nodes[name]

    cm = ControllerManager(manager_params(params), log=log, node_factory=factory, robot_description=robot_description)
    cm.load_hardware(hardware if hardware is not None else [wheel_info()])
    cm.nodes = nodes  # type: ignore[attr-defined]
    return cm, log


def loaded(cm: ControllerManager, *names: str) -> None:
    for n in names:
        cm.load_controller(n)
        cm.configure_controller(n)


def nan_to_none(v: float) -> float | None:
    return None if math.isnan(v) else v
