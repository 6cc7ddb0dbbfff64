"""position_controllers/JointGroupPositionController, effort_controllers/JointGroupEffortController and
forward_command_controller/MultiInterfaceForwardCommandController (Jazzy).

The JointGroup controllers are forward command controllers (forward_command.py: `~/commands`,
std_msgs/msg/Float64MultiArray, one value per joint) with their interface fixed — `position` or `effort` —
whatever `interface_name` a file gives (as upstream, which overwrites it in on_init; here with a warning). The
effort controller writes zero to every joint when deactivated; the position controller leaves the last command.
MultiInterfaceForwardCommandController commands several interfaces of one `joint` (`interface_names`), one
value each, in that order.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any

from diffctl.client.parameter import Parameter
from diffctl.control.controllers.forward_command import DECLS, ForwardCommandController, ForwardCommandParams
from diffctl.control.controllers.param_decl import ParamDecl, declare_all, overrides, read_declared, table
from diffctl.errors import RuntimeFailure


class _FixedInterface(ForwardCommandController):
    INTERFACE = ""

    def on_init(self) -> None:
        node = self.get_node()
        given = overrides(node).get("interface_name")
        if given not in (None, "", self.INTERFACE):
            node.get_logger().warn(f"'interface_name' {given!r} is ignored: {type(self).__name__} commands "
                                   f"'{self.INTERFACE}'")
        super().on_init()
        node.set_parameters([Parameter("interface_name", value=self.INTERFACE)])
        assert self.params is not None
        self.params = dataclasses.replace(self.params, interface_name=self.INTERFACE)


class JointGroupPositionController(_FixedInterface):
    INTERFACE = "position"
    DECLS: Mapping[str, ParamDecl] = {
        **DECLS, "interface_name": dataclasses.replace(DECLS["interface_name"], default="position", also=())}


class JointGroupEffortController(_FixedInterface):
    INTERFACE = "effort"
    DECLS: Mapping[str, ParamDecl] = {
        **DECLS, "interface_name": dataclasses.replace(DECLS["interface_name"], default="effort", also=())}
    zero_on_deactivate = True


MULTI_DECLS = table([
    ParamDecl("joint", "string", "", "Name of the joint to control"),
    ParamDecl("interface_names", "string_array", [], "Names of the interfaces to command"),
])  # fmt: skip


class MultiInterfaceForwardCommandController(ForwardCommandController):
    """`joint`'s `interface_names`, one command value each."""

    DECLS: Mapping[str, ParamDecl] = MULTI_DECLS

    def on_init(self) -> None:
        node = self.get_node()
        v = read_declared(MULTI_DECLS, overrides(node), self.get_name())
        declare_all(node, MULTI_DECLS, self.get_name())
        self._joint, self._interfaces = v["joint"], list(v["interface_names"])
        # the base's per-"joint" bookkeeping: here one entry per commanded interface
        self.params = ForwardCommandParams(tuple(self._interfaces), "")

    def _names(self) -> list[str]:
        if not self._joint:
            raise RuntimeFailure("'joint' parameter is empty")
        if not self._interfaces:
            raise RuntimeFailure("'interfaces' parameter is empty")
        return [f"{self._joint}/{i}" for i in self._interfaces]

    def on_configure(self, previous_state: Any) -> None:
        self._names()  # refuses an empty joint or interface list, as upstream's read_parameters
        super().on_configure(previous_state)
