"""forward_command_controller/ForwardCommandController and velocity_controllers/JointGroupVelocityController.

The simplest controllers: `~/commands` (std_msgs/msg/Float64MultiArray) holds one value per joint, in the order
of `joints`, written to `<joint>/<interface_name>` every update. Parameters as forward_command_controller's
`src/forward_command_controller_parameters.yaml` (ros2_controllers, jazzy): `joints` and `interface_name`
(diffctl refuses them empty); JointGroupVelocityController fixes `interface_name` to `velocity`. A "joint" may
be another controller's reference interface prefix (`diff_drive/linear` with interface `velocity`), which
chains this controller in front of that one.

A command of the wrong length, or with a non-finite or absurd value, is dropped with a warning. Nothing is
written until the first command. On deactivation the velocity controller writes zero to every joint (it
stops them), as the reference's does; the generic controller leaves the last values in place.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from diffctl.client.interfaces import cls
from diffctl.client.qos import qos_profile_system_default
from diffctl.control.controller_interface import ControllerInterface, InterfaceConfiguration, ReturnType
from diffctl.control.controllers.command_sanity import MAX_JOINT_VELOCITY, rejection
from diffctl.control.controllers.owned_endpoints import OwnedEndpoints
from diffctl.control.controllers.param_decl import (
    Check,
    ParamDecl,
    declare_all,
    overrides,
    read_declared,
    table,
    unknown_key_warnings,
)
from diffctl.control.controllers.throttled_log import ThrottledLog
from diffctl.errors import RuntimeFailure

FLOAT64_MULTI_ARRAY = "std_msgs/msg/Float64MultiArray"
_NOT_EMPTY = (Check("not_empty", ()),)

# forward_command_controller_parameters.yaml (ros2_controllers, jazzy).
DECLS = table(
    [
        ParamDecl("joints", "string_array", [], "Name of the joints to control",
                  also=(*_NOT_EMPTY, Check("unique", ()))),
        ParamDecl("interface_name", "string", "", "Name of the interface to command", also=_NOT_EMPTY),
    ]
)
VELOCITY_DECLS = {
    **DECLS,
    "interface_name": ParamDecl("interface_name", "string", "velocity", "Name of the interface to command",
                                also=(Check("one_of", (["velocity"],)),)),
}


@dataclass(frozen=True)
class ForwardCommandParams:
    joints: tuple[str, ...]
    interface_name: str = "velocity"

    @classmethod
    def from_params(
        cls, params: Mapping[str, Any], controller: str = "forward_velocity_controller", decls: Mapping = VELOCITY_DECLS
    ) -> tuple[ForwardCommandParams, list[str]]:
        v = read_declared(decls, params, controller)
        return cls(tuple(v["joints"]), v["interface_name"]), unknown_key_warnings(decls, params, controller)


class ForwardCommandController(ControllerInterface):
    DECLS: Mapping[str, ParamDecl] = DECLS
    zero_on_deactivate = False

    def __init__(self) -> None:
        super().__init__()
        self.params: ForwardCommandParams | None = None
        self._endpoints = OwnedEndpoints()
        self._handles: list[Any] = []
        self._command: tuple[float, ...] | None = None
        self._active = False

    def on_init(self) -> None:
        node = self.get_node()
        self.params, warnings = ForwardCommandParams.from_params(overrides(node), self.get_name(), self.DECLS)
        for text in warnings:
            node.get_logger().warn(text)
        declare_all(node, self.DECLS, self.get_name())

    def _names(self) -> list[str]:
        if self.params is None:
            raise RuntimeFailure(f"controller '{self.get_name()}' has no parameters: on_init was not run")
        return [f"{j}/{self.params.interface_name}" for j in self.params.joints]

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual(self._names())

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.none()

    def on_configure(self, previous_state: Any) -> None:
        self._endpoints.close_all()
        node = self.get_node()
        self._log = ThrottledLog(node.get_logger())
        self._command = None
        self._endpoints.keep(node.create_subscription(
            cls(FLOAT64_MULTI_ARRAY), "~/commands", self._on_commands, qos_profile_system_default))

    def on_activate(self, previous_state: Any) -> None:
        by_name = {ci.name: ci for ci in self.command_interfaces}
        missing = [n for n in self._names() if n not in by_name]
        if missing:
            raise RuntimeFailure(f"command interface {missing[0]!r} was not given to this controller")
        self._handles = [by_name[n] for n in self._names()]
        self._command = None  # a command sent while inactive must not move anything on activation
        self._active = True

    def on_deactivate(self, previous_state: Any) -> None:
        self._active = False
        if self.zero_on_deactivate:
            for handle in self._handles:
                handle.set_value(0.0)
        self._handles = []
        self._command = None

    def on_cleanup(self, previous_state: Any) -> None:
        self._endpoints.close_all()

    def on_shutdown(self, previous_state: Any) -> None:
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
                f"command size ({len(data)}) does not match number of interfaces ({n}): expected one value "
                f"per joint of {list(self.params.joints)}; command ignored",
            )
            return
        why = rejection(data, [MAX_JOINT_VELOCITY] * n, [f"data[{i}] ({j})" for i, j in enumerate(self.params.joints)])
        if why is not None:
            self._log.warn("bad", f"Ignoring a command: {why}; the joints keep the previous command")
            return
        self._command = tuple(float(v) for v in data)

    def update(self, time: Any, period: Any) -> ReturnType:
        command = self._command
        if command is not None:
            for handle, value in zip(self._handles, command, strict=False):
                handle.set_value(value)
        return ReturnType.OK


class JointGroupVelocityController(ForwardCommandController):
    DECLS = VELOCITY_DECLS
    zero_on_deactivate = True
