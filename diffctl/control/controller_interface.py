"""The controller plugin API: controller_interface's ControllerInterface and ChainableControllerInterface.

A controller is a class deriving from `ControllerInterface` (or `ChainableControllerInterface`), registered
under the entry-point group `diffctl.controllers` as `"<pkg>/<Class>"` (see plugin_registry). The manager
drives it exactly as controller_manager drives a C++ controller:

  load       the manager makes the controller's node (`get_node()`, a diffctl.client Node — rclpy's API —
             named `<controller>` in the manager's namespace; its arguments are the manager's, its
             `<name>.params_file`s and `use_sim_time:=true` when the manager has it), declares `update_rate`
             (the manager's rate), `is_async` and `thread_priority` on it, then calls
             `on_init()`                                          → unconfigured
             Declare the parameters here (param_decl.declare_all does it from a generate_parameter_library
             table).
  configure  `on_configure(previous_state)` — read the parameters, create publishers/subscriptions; then
             `command_interface_configuration()` / `state_interface_configuration()` are asked, and a
             chainable controller's `export_reference_interfaces()` / `export_state_interfaces()` are taken
             by the manager                                        → inactive
  activate   the manager claims the interfaces, fills `self.command_interfaces` / `self.state_interfaces`
             (in the order of the configurations; `InterfaceConfiguration.all()` gives the manager's
             order), then `on_activate(previous_state)`           → active
  update     `update(time, period)` every cycle of the controller's rate, on the manager's real-time
             thread: `time` a client `Time` (ROS clock: sim time under use_sim_time), `period` a `Duration`;
             return `ReturnType.OK` or `ReturnType.ERROR` (or raise): an error deactivates the controller
             (`on_error` first) and activates its `<name>.fallback_controllers`
  deactivate `on_deactivate(previous_state)`, then the interfaces go back   → inactive
  cleanup    `on_cleanup(previous_state)`                          → unconfigured
  unload     `on_shutdown(previous_state)` (after cleanup when inactive), the node is destroyed → finalized

Every `on_*` hook returns `CallbackReturn.SUCCESS` (or None); `FAILURE`, `ERROR` or an exception fail the
transition, and the manager reports the exception's text. Handles: `CommandInterface` (`get_value()`,
`set_value(v)`; the `.value` attribute is the fast path) and `StateInterface` (`get_value()`), both with
`get_name()` ("joint/interface"), `get_prefix_name()` and `get_interface_name()`.

Chainable controllers (controller_chaining): `update()` is the base's — `update_reference_from_subscribers`
unless in chained mode, then `update_and_write_commands`. Set `self.exported_reference_interface_names`
(suffixes, e.g. ["linear/velocity"]) before configure ends, or override `on_export_reference_interfaces()`;
the manager then owns `<controller>/<suffix>` command handles, kept in `self.reference_interfaces` (read
`.value`, NaN until written). The same goes for `exported_state_interface_names` /
`on_export_state_interfaces()` → `self.exported_state_interfaces`, written by the controller (`.value = x`)
and read by others. The manager's rules: a controller claiming another's references ("preceding") needs
that one ("following") active, or activated in the same switch (followers are then activated first); a
following controller is not deactivated while an active preceding one stays; a controller is in chained mode
while an active controller claims its references (`on_set_chained_mode(chained)` → bool, called only while it
is not active); preceding controllers update before the ones they feed, in the same cycle.
"""

from __future__ import annotations

import enum
import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal

from diffctl.client.lifecycle.managed_entity import TransitionCallbackReturn

if TYPE_CHECKING:
    from diffctl.client.duration import Duration
    from diffctl.client.node import Node
    from diffctl.client.ros_time import Time
    from diffctl.control.lifecycle import State

CallbackReturn = TransitionCallbackReturn


class ReturnType(enum.Enum):
    """controller_interface::return_type."""

    OK = 0
    ERROR = 1


class _Handle:
    """A named double shared between its owner (hardware, or a chainable controller) and its users."""

    __slots__ = ("data_type", "interface_name", "name", "prefix_name", "value")

    def __init__(self, name: str, value: float = math.nan, data_type: str = "double") -> None:
        self.name = name  # "joint/interface"
        prefix, _, iface = name.rpartition("/")
        self.prefix_name = prefix
        self.interface_name = iface
        self.value = float(value)
        self.data_type = data_type

    def get_name(self) -> str:
        return self.name

    def get_prefix_name(self) -> str:
        return self.prefix_name

    def get_interface_name(self) -> str:
        return self.interface_name

    def get_value(self) -> float:
        return self.value

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.name!r}, {self.value!r})"


class StateInterface(_Handle):
    """A read-only value (joint position, velocity, effort, a sensor reading, a controller's exported state)."""

    __slots__ = ()


class CommandInterface(_Handle):
    """A command value; while a controller holds it, only that controller writes it."""

    __slots__ = ()

    def set_value(self, v: float) -> bool:
        self.value = v
        return True


class interface_configuration_type(enum.Enum):
    ALL = "all"
    INDIVIDUAL = "individual"
    NONE = "none"


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


@dataclass(frozen=True)
class ControllerInterfaceParams:
    """What the manager gives a controller at load (controller_interface::ControllerInterfaceParams)."""

    controller_name: str
    robot_description: str = ""
    update_rate: int = 0  # the manager's rate, the default of the node's `update_rate`
    node: Any = None  # the controller's node, made by the manager


class ControllerInterface(ABC):
    """Base class of every controller plugin (the module docstring gives the call order)."""

    is_chainable_controller = False

    def __init__(self) -> None:
        self._node: Node | None = None
        self._name = ""
        self._robot_description = ""
        self._update_rate = 0
        self._state: State | None = None
        # Filled by the manager before on_activate, in the order of the interface configurations.
        self.command_interfaces: list[CommandInterface] = []
        self.state_interfaces: list[StateInterface] = []

    # --- set up by the manager -----------------------------------------------------------------------------
    def init(self, params: ControllerInterfaceParams) -> CallbackReturn:
        """Take the node and declare the base parameters, then `on_init()` (the manager calls this)."""
        self._node = params.node
        self._name = params.controller_name
        self._robot_description = params.robot_description
        self._update_rate = params.update_rate
        self.auto_declare("update_rate", int(params.update_rate))
        self.auto_declare("is_async", False)
        self.auto_declare("thread_priority", -100)
        return _returned(self.on_init())

    def get_node(self) -> Node:
        if self._node is None:
            raise RuntimeError("Lifecycle node hasn't been initialized yet!")
        return self._node

    def get_name(self) -> str:
        return self._name

    def get_robot_description(self) -> str:
        return self._robot_description

    def get_update_rate(self) -> int:
        """The rate update() runs at, in Hz (the manager's unless the controller's `update_rate` is lower)."""
        return self._update_rate

    def get_lifecycle_state(self) -> State:
        from diffctl.control.lifecycle import State

        return self._state or State.UNKNOWN

    def is_async(self) -> bool:
        return False

    def is_chainable(self) -> bool:
        return self.is_chainable_controller

    def auto_declare(self, name: str, default_value: Any) -> Any:
        """Declare `name` with `default_value` unless it is declared already; its value either way."""
        node = self.get_node()
        if not node.has_parameter(name):
            return node.declare_parameter(name, default_value).value
        return node.get_parameter(name).value

    def release_interfaces(self) -> None:
        self.command_interfaces = []
        self.state_interfaces = []

    # --- lifecycle hooks ---------------------------------------------------------------------------------
    def on_init(self) -> CallbackReturn | None:
        """Declare the parameters (raise, or return ERROR, on bad values)."""
        return CallbackReturn.SUCCESS

    @abstractmethod
    def command_interface_configuration(self) -> InterfaceConfiguration: ...

    @abstractmethod
    def state_interface_configuration(self) -> InterfaceConfiguration: ...

    def on_configure(self, previous_state: State) -> CallbackReturn | None:
        return CallbackReturn.SUCCESS

    def on_activate(self, previous_state: State) -> CallbackReturn | None:
        return CallbackReturn.SUCCESS

    def on_deactivate(self, previous_state: State) -> CallbackReturn | None:
        return CallbackReturn.SUCCESS

    def on_cleanup(self, previous_state: State) -> CallbackReturn | None:
        return CallbackReturn.SUCCESS

    def on_shutdown(self, previous_state: State) -> CallbackReturn | None:
        return CallbackReturn.SUCCESS

    def on_error(self, previous_state: State) -> CallbackReturn | None:
        """After update() returned ERROR or raised, before the manager deactivates the controller."""
        return CallbackReturn.SUCCESS

    # --- real-time loop ---------------------------------------------------------------------------------
    @abstractmethod
    def update(self, time: Time, period: Duration) -> ReturnType:
        """One control cycle: read the state interfaces, write the command interfaces."""

    # Chainable API, as the manager sees every controller (the plain ones export nothing).
    def export_reference_interfaces(self) -> list[CommandInterface]:
        return []

    def export_state_interfaces(self) -> list[StateInterface]:
        return []

    def set_chained_mode(self, chained_mode: bool) -> bool:
        return False

    def is_in_chained_mode(self) -> bool:
        return False


class ChainableControllerInterface(ControllerInterface):
    """A controller other controllers can be chained in front of (controller_interface's chainable base)."""

    is_chainable_controller = True

    def __init__(self) -> None:
        super().__init__()
        self.exported_reference_interface_names: list[str] = []
        self.reference_interfaces: list[CommandInterface] = []
        self.exported_state_interface_names: list[str] = []
        self.exported_state_interfaces: list[StateInterface] = []
        self._chained_mode = False

    def update(self, time: Time, period: Duration) -> ReturnType:
        if not self._chained_mode:
            ret = self.update_reference_from_subscribers(time, period)
            if ret is not ReturnType.OK:
                return ret
        return self.update_and_write_commands(time, period)

    @abstractmethod
    def update_reference_from_subscribers(self, time: Time, period: Duration) -> ReturnType:
        """Outside chained mode: the references from the controller's topics, into `reference_interfaces`."""

    @abstractmethod
    def update_and_write_commands(self, time: Time, period: Duration) -> ReturnType:
        """The control law on the references (whoever wrote them), writing the command interfaces."""

    # --- exported interfaces ----------------------------------------------------------------------------
    def on_export_reference_interfaces(self) -> list[CommandInterface]:
        """`<controller>/<suffix>` for every `exported_reference_interface_names` entry, NaN (no reference)."""
        return [CommandInterface(f"{self._name}/{n}", math.nan) for n in self.exported_reference_interface_names]

    def on_export_state_interfaces(self) -> list[StateInterface]:
        return [StateInterface(f"{self._name}/{n}", math.nan) for n in self.exported_state_interface_names]

    def export_reference_interfaces(self) -> list[CommandInterface]:
        self.reference_interfaces = self._checked(self.on_export_reference_interfaces(), "reference")
        return list(self.reference_interfaces)

    def export_state_interfaces(self) -> list[StateInterface]:
        self.exported_state_interfaces = self._checked(self.on_export_state_interfaces(), "state")
        return list(self.exported_state_interfaces)

    def _checked(self, handles: list[Any], kind: str) -> list[Any]:
        seen: set[str] = set()
        for h in handles:
            if not h.prefix_name.startswith(self._name):
                raise RuntimeError(
                    f"The prefix of the interface '{h.prefix_name}' should begin with the controller's name "
                    f"'{self._name}'. This is mandatory for {kind} interfaces."
                )
            if h.name in seen:
                raise RuntimeError(f"controller '{self._name}' exports the {kind} interface '{h.name}' twice")
            seen.add(h.name)
        return list(handles)

    # --- chained mode -----------------------------------------------------------------------------------
    def set_chained_mode(self, chained_mode: bool) -> bool:
        from diffctl.control.lifecycle import State

        if self._state is State.ACTIVE:
            self.get_node().get_logger().error(
                "Can not change controller's chained mode because it is no in 'unconfigured' state. "
                "Current state is 'active'."
            )
            return False
        if self.on_set_chained_mode(chained_mode) is False:
            return False
        self._chained_mode = chained_mode
        for ref in self.reference_interfaces:  # the references restart unset: nobody has written them yet
            ref.value = math.nan
        return True

    def is_in_chained_mode(self) -> bool:
        return self._chained_mode

    def on_set_chained_mode(self, chained_mode: bool) -> bool:
        return True


def _returned(value: Any) -> CallbackReturn:
    """A hook's result as a CallbackReturn (None is success)."""
    return CallbackReturn.SUCCESS if value is None else value
