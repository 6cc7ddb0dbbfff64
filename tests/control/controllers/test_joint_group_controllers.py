"""JointGroupPositionController, JointGroupEffortController and MultiInterfaceForwardCommandController driven
directly (real client nodes), with the joints and commands of upstream's tests (ros2_controllers jazzy:
test_joint_group_position_controller, test_joint_group_effort_controller,
test_multi_interface_forward_command_controller): commands {10, 20, 30}; {10, 20} is refused."""

from __future__ import annotations

import pytest
from controller_harness import START_NS, activate, configure, hand_interfaces, make_controller, update

from diffctl.control.controllers.joint_group_controllers import (
    JointGroupEffortController,
    JointGroupPositionController,
    MultiInterfaceForwardCommandController,
)
from diffctl.control.lifecycle import State
from diffctl.errors import RuntimeFailure

pytestmark = pytest.mark.usefixtures("client_bus")

JOINTS = ["joint1", "joint2", "joint3"]


def running(cls_, name, params, initial=1.1):
    c = make_controller(cls_, name, params)
    configure(c)
    cmd, _ = hand_interfaces(c, {n: initial for n in c.command_interface_configuration().names})
    activate(c)
    return c, cmd


@pytest.mark.parametrize(("cls_", "kind", "after_deactivate"), [
    (JointGroupPositionController, "position", [10.0, 20.0, 30.0]),
    (JointGroupEffortController, "effort", [0.0, 0.0, 0.0]),
])
def test_joint_group_controllers_forward_their_interface(cls_, kind, after_deactivate) -> None:
    name = f"test_joint_group_{kind}_controller"
    # interface_name is the controller's own, whatever a file says (upstream overwrites it in on_init)
    c, cmd = running(cls_, name, {"joints": JOINTS, "interface_name": "velocity"})
    assert "'interface_name' 'velocity' is ignored" in c.probe.log.text("WARN")
    assert c.get_node().get_parameter("interface_name").value == kind
    assert list(cmd) == [f"{j}/{kind}" for j in JOINTS]
    update(c, START_NS, 0.01)
    assert [h.value for h in cmd.values()] == [1.1] * 3  # NoCommandCheckTest: nothing written
    c.probe.deliver(f"/{name}/commands", {"data": [10.0, 20.0]})  # WrongCommandCheckTest
    update(c, START_NS, 0.01)
    assert [h.value for h in cmd.values()] == [1.1] * 3
    c.probe.deliver(f"/{name}/commands", {"data": [10.0, 20.0, 30.0]})  # CommandCallbackTest
    update(c, START_NS, 0.01)
    assert [h.value for h in cmd.values()] == [10.0, 20.0, 30.0]
    c.on_deactivate(State.ACTIVE)  # StopJointsOnDeactivateTest (effort)
    assert [h.value for h in cmd.values()] == after_deactivate


def test_multi_interface_forward_command_controller() -> None:
    name = "test_multi_interface_forward_command_controller"
    c, cmd = running(MultiInterfaceForwardCommandController, name,
                     {"joint": "joint1", "interface_names": ["position", "velocity", "effort"]})
    assert c.command_interface_configuration().names == ["joint1/position", "joint1/velocity", "joint1/effort"]
    c.probe.deliver(f"/{name}/commands", {"data": [10.0, 20.0, 30.0]})
    update(c, START_NS, 0.01)
    assert [h.value for h in cmd.values()] == [10.0, 20.0, 30.0]
    c.probe.deliver(f"/{name}/commands", {"data": [10.0, 20.0]})
    assert "command size (2) does not match number of interfaces (3)" in c.probe.log.text("WARN")
    for params in ({"joint": "joint1"}, {"interface_names": ["position"]}):  # JointsParameterNotSet / Empty
        bad = make_controller(MultiInterfaceForwardCommandController, name, params)
        with pytest.raises(RuntimeFailure):
            bad.on_configure(State.UNCONFIGURED)
