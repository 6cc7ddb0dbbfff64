"""A controller plugin that works for a while, then raises in update() — the fault the manager must contain.

Installed for a test through a throw-away distribution (entry point group `diffctl.controllers`, type
`diffctl_faults/RaisingController`); parameter `fail_after` (cycles, default 20).
"""

from __future__ import annotations

from typing import Any

from diffctl.control.controller_interface import ControllerInterface, InterfaceConfiguration, ReturnType


class RaisingController(ControllerInterface):
    def on_init(self) -> None:
        self.fail_after = self.auto_declare("fail_after", 20)
        self.cycles = 0

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.none()

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual(["base_link_to_left_wheel/velocity"])

    def update(self, time: Any, period: Any) -> ReturnType:
        self.cycles += 1
        if self.cycles > self.fail_after:
            raise RuntimeError(f"injected fault after {self.fail_after} cycles")
        return ReturnType.OK
