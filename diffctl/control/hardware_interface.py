"""The hardware plugin API (hardware_interface::SystemInterface) and the `<ros2_control>` block it is built from.

`HardwareInfo` is one `<ros2_control>` element: its hardware plugin and `<param>`s, and the joints (and
sensors, GPIOs) with their command and state interfaces. A hardware plugin derives from
`HardwareComponent`, is registered under the entry point group `diffctl.hardware`, and exports handles
that the resource manager loans to controllers. Raising from a hook fails that lifecycle transition.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field

from diffctl.control.controller_interface import CommandInterface, ReturnType, StateInterface

__all__ = [
    "CommandInterface",
    "ComponentInfo",
    "HardwareComponent",
    "HardwareInfo",
    "InterfaceInfo",
    "ReturnType",
    "StateInterface",
]


@dataclass(frozen=True)
class InterfaceInfo:
    """`<command_interface name="velocity">` / `<state_interface>` with optional min, max, initial_value (a min or
    max not given is -inf or inf)."""

    name: str
    min: float = -math.inf
    max: float = math.inf
    initial_value: float | None = None
    data_type: str = "double"
    parameters: dict[str, str] = field(default_factory=dict)
    enable_limits: bool = True  # false: its min/max are no joint limit (`<limits enable="false"/>`)


@dataclass(frozen=True)
class ComponentInfo:
    """A `<joint>`, `<sensor>` or `<gpio>` of a `<ros2_control>` block."""

    name: str
    type: str = "joint"
    command_interfaces: tuple[InterfaceInfo, ...] = ()
    state_interfaces: tuple[InterfaceInfo, ...] = ()
    parameters: dict[str, str] = field(default_factory=dict)
    enable_limits: bool = True  # false: no limits are enforced on this joint


@dataclass(frozen=True)
class HardwareInfo:
    """One `<ros2_control name=… type=system>` block."""

    name: str
    type: str = "system"
    plugin_name: str = ""
    hardware_parameters: dict[str, str] = field(default_factory=dict)
    joints: tuple[ComponentInfo, ...] = ()
    sensors: tuple[ComponentInfo, ...] = ()
    gpios: tuple[ComponentInfo, ...] = ()
    rw_rate: int = 0  # 0 = the manager's rate
    source: str | None = None  # file the block came from, for error messages

    @property
    def components(self) -> tuple[ComponentInfo, ...]:
        return self.joints + self.sensors + self.gpios


class HardwareComponent(ABC):
    """Base class of hardware plugins (a ros2_control SystemInterface).

    The default `export_*_interfaces` create one handle per interface of the block, starting at its
    `initial_value` (NaN when none is given, as ros2_control does) and keep them in `self.states` /
    `self.commands` keyed by "joint/interface"; plugins usually only implement read() and write().
    """

    def __init__(self) -> None:
        self.name: str = ""
        self.info: HardwareInfo = HardwareInfo(name="")
        self.states: dict[str, StateInterface] = {}
        self.commands: dict[str, CommandInterface] = {}
        self.log = None  # set by the resource manager: a Logger (info/warn/error)
        self.update_rate: int = 0  # the controller manager's update_rate, set before on_init
        self.cancel = None  # a threading.Event set when the manager stops (to end waits in on_init/on_activate)

    # --- lifecycle hooks ----------------------------------------------------------------------------------
    def on_init(self, info: HardwareInfo) -> None:
        self.info = info
        self.name = info.name

    def on_configure(self) -> None:
        pass

    def on_cleanup(self) -> None:
        pass

    def on_activate(self) -> None:
        pass

    def on_deactivate(self) -> None:
        pass

    def on_shutdown(self) -> None:
        pass

    # --- interfaces -----------------------------------------------------------------------------------------
    def export_state_interfaces(self) -> list[StateInterface]:
        if not self.states:
            for comp in self.info.components:
                for it in comp.state_interfaces:
                    init = math.nan if it.initial_value is None else it.initial_value
                    self.states[f"{comp.name}/{it.name}"] = StateInterface(f"{comp.name}/{it.name}", init, it.data_type)
        return list(self.states.values())

    def export_command_interfaces(self) -> list[CommandInterface]:
        if not self.commands:
            for comp in self.info.components:
                for it in comp.command_interfaces:
                    init = math.nan if it.initial_value is None else it.initial_value
                    self.commands[f"{comp.name}/{it.name}"] = CommandInterface(
                        f"{comp.name}/{it.name}", init, it.data_type
                    )
        return list(self.commands.values())

    def prepare_command_mode_switch(self, start: list[str], stop: list[str]) -> bool:
        return True

    def perform_command_mode_switch(self, start: list[str], stop: list[str]) -> bool:
        return True

    # --- real-time loop -------------------------------------------------------------------------------------
    @abstractmethod
    def read(self, time_ns: int, period_s: float) -> ReturnType:
        """Copy the hardware's state into the exported state interfaces."""

    @abstractmethod
    def write(self, time_ns: int, period_s: float) -> ReturnType:
        """Send the command interfaces' values to the hardware."""
