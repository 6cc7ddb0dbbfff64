"""velocity_controllers/JointGroupVelocityController: forwards ~/commands to the joints' velocity interfaces.

The simplest controller (forward_command_controller): parameter `joints`, interface fixed to `velocity`;
`~/commands` (std_msgs/msg/Float64MultiArray) holds one value per joint, in the order of `joints`. A command
of the wrong length, or with a non-finite or absurd value, is dropped with a warning. Nothing is written until
the first command; deactivation writes zero to every joint, as the reference's velocity controller does.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from diffctl.control.controller_interface import ControllerInterface, InterfaceConfiguration, ReturnType
from diffctl.control.controllers.command_sanity import MAX_JOINT_VELOCITY, rejection
from diffctl.control.controllers.owned_endpoints import OwnedEndpoints
from diffctl.control.controllers.param_values import ParamReader
from diffctl.control.controllers.throttled_log import ThrottledLog
from diffctl.errors import RuntimeFailure

FLOAT64_MULTI_ARRAY = "std_msgs/msg/Float64MultiArray"


@dataclass(frozen=True)
class ForwardCommandParams:
    joints: tuple[str, ...]
    interface_name: str = "velocity"

    @classmethod
    def from_params(
        cls, params: Mapping[str, Any], controller: str = "forward_velocity_controller"
    ) -> tuple[ForwardCommandParams, list[str]]:
        r = ParamReader(params, controller)
        joints = r.str_list("joints", [], non_empty=True)
        iface = r.str("interface_name", "velocity", choices=["velocity"])
        return cls(joints, iface), r.unknown_key_warnings()


class JointGroupVelocityController(ControllerInterface):
    def __init__(self) -> None:
        super().__init__()
        self.params: ForwardCommandParams | None = None
        self._endpoints = OwnedEndpoints()
        self._handles: list[Any] = []
        self._command: tuple[float, ...] | None = None
        self._active = False

    def on_init(self) -> None:
        self.params, warnings = ForwardCommandParams.from_params(self.node.params, self.name)
        for text in warnings:
            self.node.log.warn(text)

    def _names(self) -> list[str]:
        if self.params is None:
            raise RuntimeFailure(f"controller '{self.name}' has no parameters: on_init was not run")
        return [f"{j}/{self.params.interface_name}" for j in self.params.joints]

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual(self._names())

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.none()

    def on_configure(self) -> None:
        self._endpoints.close_all()
        self._log = ThrottledLog(self.node.log)
        self._command = None
        self._endpoints.keep(self.node.create_subscription("~/commands", FLOAT64_MULTI_ARRAY, self._on_commands))

    def on_activate(self) -> None:
        by_name = {ci.name: ci for ci in self.command_interfaces}
        missing = [n for n in self._names() if n not in by_name]
        if missing:
            raise RuntimeFailure(f"command interface {missing[0]!r} was not given to this controller")
        self._handles = [by_name[n] for n in self._names()]
        self._command = None  # a command sent while inactive must not move anything on activation
        self._active = True

    def on_deactivate(self) -> None:
        self._active = False
        for handle in self._handles:
            handle.set_value(0.0)
        self._handles = []
        self._command = None

    def on_cleanup(self) -> None:
        self._endpoints.close_all()

    def on_shutdown(self) -> None:
        self._endpoints.close_all()

    def _on_commands(self, msg: Any) -> None:
        if not self._active:
            self._log.warn("inactive", "Can't accept new commands. subscriber is inactive")
            return
        data = list(msg.data)
        n = len(self._handles)
        if len(data) != n:
            self._log.warn(
                "size",
                f"command size ({len(data)}) does not match number of interfaces ({n}): expected one velocity "
                f"per joint of {list(self.params.joints)}; command ignored",
            )
            return
        why = rejection(data, [MAX_JOINT_VELOCITY] * n, [f"data[{i}] ({j})" for i, j in enumerate(self.params.joints)])
        if why is not None:
            self._log.warn("bad", f"Ignoring a command: {why}; the joints keep the previous command")
            return
        self._command = tuple(float(v) for v in data)

    def update(self, time_ns: int, period_s: float) -> ReturnType:
        command = self._command
        if command is not None:
            for handle, value in zip(self._handles, command, strict=False):
                handle.set_value(value)
        return ReturnType.OK
