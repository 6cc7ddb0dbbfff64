"""Fake controllers, a recording node and hardware info builders for manager unit tests (no bus)."""

from __future__ import annotations

import math
from typing import Any

from diffctl.control.controller_interface import ControllerInterface, InterfaceConfiguration, ReturnType
from diffctl.control.hardware_interface import ComponentInfo, HardwareInfo, InterfaceInfo
from diffctl.control.manager import ControllerManager
from diffctl.control.params import manager_params
from diffctl.control.plugin_registry import register_controller
from tests.control.controllers.controller_fakes import RecordingLog


class FakeNode:
    def __init__(self, name: str, params: dict[str, Any]) -> None:
        self.name = name
        self.params = params
        self.log = RecordingLog()
        self.closed = False

    def create_publisher(self, *a: Any, **k: Any) -> None:
        return None

    def create_subscription(self, *a: Any, **k: Any) -> None:
        return None

    def now_ns(self) -> int:
        return 0

    def resolve(self, name: str) -> str:
        return name

    def close(self) -> None:
        self.closed = True


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
        self.raise_in = set(self.node.params.get("raise_in", []))
        self._hook("on_init")

    def command_interface_configuration(self) -> InterfaceConfiguration:
        cmds = self.node.params.get("commands")
        return InterfaceConfiguration.all() if cmds == "all" else InterfaceConfiguration.individual(cmds or [])

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual(self.node.params.get("states", []))

    def on_configure(self) -> None:
        self._hook("on_configure")

    def on_activate(self) -> None:
        self._hook("on_activate")

    def on_deactivate(self) -> None:
        self._hook("on_deactivate")
        for c in self.command_interfaces:
            c.set_value(0.0)

    def on_cleanup(self) -> None:
        self._hook("on_cleanup")

    def on_shutdown(self) -> None:
        self._hook("on_shutdown")

    def update(self, time_ns: int, period_s: float) -> ReturnType:
        self.updates.append((time_ns, period_s))
        if "update" in self.raise_in:
            raise ValueError("update exploded")
        for c in self.command_interfaces:
            c.set_value(float(self.node.params.get("command_value", 1.0)))
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
    **flat: Any,
) -> tuple[ControllerManager, RecordingLog]:
    """A manager with mock hardware and fake controllers `{name: params}` registered as test_controllers/Fake."""
    params: dict[str, Any] = {"update_rate": update_rate, **flat}
    ctrl_params = controllers or {}
    for name in ctrl_params:
        params[f"{name}.type"] = "test_controllers/Fake"
    log = RecordingLog()
    nodes: dict[str, FakeNode] = {}

    def factory(name: str, p: dict[str, Any]) -> FakeNode:
        nodes[name] = FakeNode(name, {**p, **ctrl_params.get(name, {})})
        return nodes[name]

    cm = ControllerManager(manager_params(params), log=log, node_factory=factory)
    cm.load_hardware(hardware if hardware is not None else [wheel_info()])
    cm.nodes = nodes  # type: ignore[attr-defined]
    return cm, log


def loaded(cm: ControllerManager, *names: str) -> None:
    for n in names:
        cm.load_controller(n)
        cm.configure_controller(n)


def nan_to_none(v: float) -> float | None:
    return None if math.isnan(v) else v
