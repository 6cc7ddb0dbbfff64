"""A forward command controller chained in front of diff_drive_controller through its reference interfaces
`<controller>/linear/velocity` and `<controller>/angular/velocity`: the real manager, resource manager and
mock hardware, the real controllers on real client nodes."""

from __future__ import annotations

from typing import Any

import pytest
from controller_harness import NS, Probe, RecordingThread, make_node

from diffctl.client.ros_logging import get_logger
from diffctl.control import realtime_publisher
from diffctl.control.hardware_interface import ComponentInfo, HardwareInfo, InterfaceInfo
from diffctl.control.lifecycle import State
from diffctl.control.manager import ControllerManager
from diffctl.control.params import manager_params
from diffctl.control.switching import STRICT

DDC = {
    "left_wheel_names": ["left_wheel"],
    "right_wheel_names": ["right_wheel"],
    "wheel_separation": 0.3,
    "wheel_radius": 0.04,
    "cmd_vel_timeout": 0.0,
}
FWD = {"joints": ["ddc/linear", "ddc/angular"], "interface_name": "velocity"}
REFS = ["ddc/linear/velocity", "ddc/angular/velocity"]
pytestmark = pytest.mark.usefixtures("client_bus")


def hardware() -> HardwareInfo:
    joint = lambda name: ComponentInfo(  # noqa: E731
        name,
        command_interfaces=(InterfaceInfo("velocity"),),
        state_interfaces=(InterfaceInfo("position"), InterfaceInfo("velocity")),
    )
    return HardwareInfo(
        "robot",
        plugin_name="mock_components/GenericSystem",
        hardware_parameters={"calculate_dynamics": "true"},
        joints=(joint("left_wheel"), joint("right_wheel")),
    )


class Rig:
    def __init__(self) -> None:
        self.nodes: dict[str, Probe] = {}
        own = {"ddc": DDC, "fwd": FWD}
        recorder = realtime_publisher._thread = RecordingThread()

        def factory(name: str, _arguments: list[str]) -> Any:
            node = make_node(name, own[name])
            self.nodes[name] = Probe(node, recorder)
            return node

        params = {
            "update_rate": 100,
            "ddc.type": "diff_drive_controller/DiffDriveController",
            "fwd.type": "forward_command_controller/ForwardCommandController",
        }
        self.cm = ControllerManager(manager_params(params), log=get_logger("test_chained"), node_factory=factory)
        self.cm.load_hardware([hardware()])
        for name in ("ddc", "fwd"):
            self.cm.load_controller(name)
            self.cm.configure_controller(name)
        self.t_ns = 100 * NS

    def cycle(self, n: int = 1) -> None:
        for _ in range(n):
            self.t_ns += NS // 100
            for node in self.nodes.values():
                node.time_ns = self.t_ns
            self.cm.read(self.t_ns, 0.01)
            self.cm.update(self.t_ns, 0.01)
            self.cm.write(self.t_ns, 0.01)

    def wheels(self) -> tuple[float, float]:
        return self.cm.state_value("left_wheel/velocity"), self.cm.state_value("right_wheel/velocity")

    def ddc(self) -> Any:
        return self.cm.controllers["ddc"].instance


def test_reference_interfaces_exist_once_configured_and_are_available_while_active():
    rig = Rig()
    rm = rig.cm.rm
    assert [rm.reference_owner.get(r) for r in REFS] == ["ddc", "ddc"]
    assert not any(rm.command_available(r) for r in REFS)
    ok, msg = rig.cm.switch_controller(["fwd"], [], STRICT)
    assert not ok and "chained in front of 'ddc'" in msg and "not active" in msg
    assert rig.cm.switch_controller(["ddc"], [], STRICT) == (True, "")
    assert all(rm.command_available(r) for r in REFS)


def test_a_forward_controller_chained_in_front_drives_the_wheels():
    rig = Rig()
    assert rig.cm.switch_controller(["fwd", "ddc"], [], STRICT) == (True, "")  # ddc is activated first
    assert rig.ddc().is_in_chained_mode()
    assert [mc.name for mc in rig.cm._active] == ["fwd", "ddc"]  # the preceding controller updates first
    assert {r: rig.cm.interface_users().get(r) for r in REFS} == {r: "fwd" for r in REFS}

    rig.nodes["fwd"].deliver("/fwd/commands", {"data": [0.2, 0.3]})
    rig.cycle(2)  # the mock hardware's states follow the commands at its next read
    left, right = rig.wheels()
    assert left == pytest.approx((0.2 - 0.3 * 0.15) / 0.04) and right == pytest.approx((0.2 + 0.3 * 0.15) / 0.04)
    # In chained mode the controller's own topic is not read.
    rig.nodes["ddc"].deliver("/ddc/cmd_vel", {"twist": {"linear": {"x": 1.0}}})
    rig.cycle(3)
    assert rig.wheels()[0] == pytest.approx(left)


def test_the_following_controller_stays_while_one_is_chained_in_front_and_leaves_chained_mode_after():
    rig = Rig()
    rig.cm.switch_controller(["fwd", "ddc"], [], STRICT)
    ok, msg = rig.cm.switch_controller([], ["ddc"], STRICT)
    assert not ok and "'fwd' is chained in front of it" in msg
    assert rig.cm.controllers["ddc"].state is State.ACTIVE

    assert rig.cm.switch_controller([], ["fwd"], STRICT) == (True, "")
    assert not rig.ddc().is_in_chained_mode()
    rig.cycle(2)
    assert rig.wheels() == (0.0, 0.0)  # leaving chained mode stops the wheels until a command arrives
    rig.nodes["ddc"].deliver("/ddc/cmd_vel", {"twist": {"linear": {"x": 0.1}}})
    rig.cycle(2)
    assert rig.wheels() == pytest.approx((0.1 / 0.04, 0.1 / 0.04))


def test_cleanup_removes_the_reference_interfaces():
    rig = Rig()
    rig.cm.unload_controller("fwd")
    rig.cm.cleanup_controller("ddc")
    assert not any(r in rig.cm.rm.command_interfaces for r in REFS) and not rig.cm.rm.reference_owner
    rig.cm.configure_controller("ddc")
    assert all(r in rig.cm.rm.command_interfaces for r in REFS)


def test_claiming_all_command_interfaces_takes_the_hardware_ones_not_references():
    rig = Rig()
    cfg = type(rig.ddc().command_interface_configuration()).all()
    assert sorted(rig.cm._resolve(cfg, command=True)) == ["left_wheel/velocity", "right_wheel/velocity"]


def test_chaining_in_front_of_a_running_controller_stops_the_wheels_until_the_new_source_commands():
    rig = Rig()
    rig.cm.switch_controller(["ddc"], [], STRICT)
    rig.nodes["ddc"].deliver("/ddc/cmd_vel", {"twist": {"linear": {"x": 0.1}}})
    rig.cycle(2)
    assert rig.wheels() == pytest.approx((2.5, 2.5))
    assert rig.cm.switch_controller(["fwd"], [], STRICT) == (True, "")
    rig.cycle(3)
    assert rig.wheels() == (0.0, 0.0)
    rig.nodes["fwd"].deliver("/fwd/commands", {"data": [0.04, 0.0]})
    rig.cycle(2)
    assert rig.wheels() == pytest.approx((1.0, 1.0))
