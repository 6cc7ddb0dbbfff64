"""The controller plugin API (controller_interface::ControllerInterface) and the interface handles it uses.

Hardware owns named doubles; the manager loans them to controllers as `CommandInterface` (exclusive) and
`StateInterface` (shared, read-only) handles. A controller plugin derives from `ControllerInterface`,
is registered under the entry point group `diffctl.controllers`, and is driven by the controller manager
through the standard lifecycle: on_init → on_configure → on_activate → update()* → on_deactivate → …
Raising from an `on_*` hook makes that transition fail with the exception's message.
"""

from __future__ import annotations

import enum
import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, Protocol

if TYPE_CHECKING:
    from collections.abc import Callable


class ReturnType(enum.Enum):
    OK = 0
    ERROR = 1


class _Handle:
    """A named double shared between hardware (which owns it) and the manager/controllers (which borrow it)."""

    __slots__ = ("data_type", "interface_name", "name", "prefix_name", "value")

    def __init__(self, name: str, value: float = math.nan, data_type: str = "double") -> None:
        self.name = name  # "joint/interface", as ros2_control's get_name()
        prefix, _, iface = name.rpartition("/")
        self.prefix_name = prefix
        self.interface_name = iface
        self.value = float(value)
        self.data_type = data_type

    def get_value(self) -> float:
        return self.value

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.name!r}, {self.value!r})"


class StateInterface(_Handle):
    """A read-only value exported by hardware (joint position, velocity, effort, sensor readings)."""

    __slots__ = ()


class CommandInterface(_Handle):
    """A command value exported by hardware; while a controller holds it, only that controller writes it."""

    __slots__ = ()

    def set_value(self, v: float) -> None:
        self.value = v


@dataclass(frozen=True)
class InterfaceConfiguration:
    """Which interfaces a controller claims: all of them, the listed ones ("joint/interface"), or none."""

    type: Literal["all", "individual", "none"] = "none"
    names: list[str] = field(default_factory=list)

    @classmethod
    def all(cls) -> InterfaceConfiguration:
        return cls("all", [])

    @classmethod
    def none(cls) -> InterfaceConfiguration:
        return cls("none", [])

    @classmethod
    def individual(cls, names: list[str]) -> InterfaceConfiguration:
        return cls("individual", list(names))


class Logger(Protocol):
    def debug(self, text: str) -> None: ...
    def info(self, text: str) -> None: ...
    def warn(self, text: str) -> None: ...
    def error(self, text: str) -> None: ...


class ControllerNode(Protocol):
    """What a controller sees of its node `/<controller name>` (a thin layer over a bus Node).

    `params` holds the controller's parameters, flattened to dotted keys ("linear.x.max_velocity"), merged
    from the manager's parameter file(s), `<name>.params_file` and the spawner's --param-file.
    """

    name: str
    params: dict[str, Any]
    log: Logger

    def create_publisher(self, topic: str, type_name: str, latched: bool = False, depth: int = 10) -> Any: ...
    def create_subscription(
        self, topic: str, type_name: str, callback: Callable[[Any], None], latched: bool = False
    ) -> Any: ...
    def now_ns(self) -> int: ...
    def resolve(self, name: str) -> str: ...
    # Declared parameters (rclcpp's): a node without them (a test double) is only validated against the table.
    def declare_parameter(self, name: str, default: Any, descriptor: Any = None) -> Any: ...
    def get_parameter(self, name: str) -> Any: ...
    def set_parameters(self, values: dict[str, Any]) -> list[str | None]: ...
    def add_on_set_parameters_callback(self, cb: Callable[[dict[str, Any]], str | None]) -> None: ...


class ControllerInterface(ABC):
    """Base class of every controller plugin (see module docstring for the call order)."""

    def __init__(self) -> None:
        # Set by the manager before on_init.
        self.name: str = ""
        self.node: ControllerNode = None  # type: ignore[assignment]
        self.update_rate: int = 0  # 0 = the manager's rate
        self.robot_description: str = ""  # the SDF/URDF text the manager was started with
        # Assigned by the manager before on_activate, in the order of the interface configurations.
        self.command_interfaces: list[CommandInterface] = []
        self.state_interfaces: list[StateInterface] = []

    # --- lifecycle hooks: raise to fail the transition --------------------------------------------------
    def on_init(self) -> None:
        """Declare and validate parameters from `self.node.params`; raise ParameterError on bad values."""

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.none()

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.none()

    def on_configure(self) -> None:
        """Create publishers and subscriptions here, as ros2_control controllers do."""

    def on_activate(self) -> None:
        pass

    def on_deactivate(self) -> None:
        pass

    def on_cleanup(self) -> None:
        pass

    def on_shutdown(self) -> None:
        pass

    def on_error(self) -> None:
        """Called after update() returned ERROR or raised, before the manager deactivates the controller."""

    # --- real-time loop ---------------------------------------------------------------------------------
    @abstractmethod
    def update(self, time_ns: int, period_s: float) -> ReturnType:
        """One control cycle: read the state interfaces, write the command interfaces."""

    # --- helpers -----------------------------------------------------------------------------------------
    def param(self, name: str, default: Any = None) -> Any:
        return self.node.params.get(name, default) if self.node is not None else default


class ChainableControllerInterface(ControllerInterface):
    """A controller other controllers can be chained in front of (controller_interface's chainable base).

    It exports reference interfaces, `<controller>/<name>` command handles, when configured. While another
    active controller claims them the manager puts it in chained mode: it then takes its references from
    those handles, written by the preceding controller earlier in the same cycle, instead of its topics.
    """

    is_chainable = True

    def __init__(self) -> None:
        super().__init__()
        self.reference_interfaces: list[CommandInterface] = []
        self._chained_mode = False

    def reference_interface_names(self) -> list[str]:
        """The suffixes after `<controller>/` (e.g. "linear/velocity"); override in the controller."""
        return []

    def export_reference_interfaces(self) -> list[CommandInterface]:
        """Fresh handles `<controller>/<suffix>`, NaN (no reference) until someone writes them."""
        names = self.reference_interface_names()
        self.reference_interfaces = [CommandInterface(f"{self.name}/{n}", math.nan) for n in names]
        return list(self.reference_interfaces)

    def is_in_chained_mode(self) -> bool:
        return self._chained_mode

    def set_chained_mode(self, chained: bool) -> None:
        """Switch where the references come from; the references restart as NaN (nothing written)."""
        self._chained_mode = chained
        for ref in self.reference_interfaces:
            ref.set_value(math.nan)
        self.on_set_chained_mode(chained)

    def on_set_chained_mode(self, chained: bool) -> None:
        """Hook for the controller (e.g. to reset its command buffers)."""
