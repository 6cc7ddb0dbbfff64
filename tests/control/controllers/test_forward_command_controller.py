"""JointGroupVelocityController driven directly (a real client node): forwarding, bad commands dropped, zero on
deactivate."""

from __future__ import annotations

import math

import pytest
from controller_harness import NS, activate, configure, hand_interfaces, make_controller, update

from diffctl.control.controllers.forward_command import JointGroupVelocityController
from diffctl.control.lifecycle import State
from diffctl.errors import ParameterError

pytestmark = pytest.mark.usefixtures("client_bus")

NAME = "forward_velocity_controller"
TOPIC = f"/{NAME}/commands"


def active():
    c = make_controller(JointGroupVelocityController, NAME, {"joints": ["left", "right"]})
    configure(c)
    cmd, _ = hand_interfaces(c)
    activate(c)
    return c, cmd


def values(cmd) -> list[float]:
    return [cmd["left/velocity"].value, cmd["right/velocity"].value]


def test_claims_the_velocity_interfaces_in_joint_order():
    c = make_controller(JointGroupVelocityController, NAME, {"joints": ["b", "a"]})
    assert c.command_interface_configuration().names == ["b/velocity", "a/velocity"]
    assert c.state_interface_configuration().type == "none"


def test_forwards_the_last_command_every_update():
    c, cmd = active()
    for h in cmd.values():
        h.value = math.nan
    update(c, NS, 0.01)
    assert all(math.isnan(v) for v in values(cmd))  # nothing written before the first command
    c.probe.deliver(TOPIC, {"data": [1.5, -2.0]})
    update(c, NS, 0.01)
    assert values(cmd) == [1.5, -2.0]


@pytest.mark.parametrize(
    ("data", "reason"),
    [
        ([1.0], "command size (1) does not match number of interfaces (2)"),
        ([1.0, 2.0, 3.0], "command size (3)"),
        ([math.nan, 0.0], "data[0] (left) is nan"),
        ([0.0, math.inf], "data[1] (right) is inf"),
        ([0.0, 1e9], "exceeds the sanity bound"),
    ],
)
def test_bad_commands_are_dropped(data, reason):
    c, cmd = active()
    c.probe.deliver(TOPIC, {"data": [0.5, 0.5]})
    c.probe.deliver(TOPIC, {"data": data})
    update(c, NS, 0.01)
    assert values(cmd) == [0.5, 0.5]
    assert reason in c.probe.log.text("WARN")


def test_deactivate_writes_zero_and_reactivation_waits_for_a_new_command():
    c, cmd = active()
    c.probe.deliver(TOPIC, {"data": [0.5, 0.5]})
    update(c, NS, 0.01)
    c.on_deactivate(State.ACTIVE)
    assert values(cmd) == [0.0, 0.0]
    c.probe.deliver(TOPIC, {"data": [3.0, 3.0]})
    assert "subscriber is inactive" in c.probe.log.text("WARN")
    cmd, _ = hand_interfaces(c)
    activate(c)
    update(c, NS, 0.01)
    assert values(cmd) == [0.0, 0.0]


@pytest.mark.parametrize(
    ("params", "field"),
    [({}, "joints"), ({"joints": []}, "joints"), ({"joints": ["a"], "interface_name": "position"}, "interface_name")],
)
def test_bad_parameters(params, field):
    with pytest.raises(ParameterError) as e:
        make_controller(JointGroupVelocityController, NAME, params)
    assert e.value.field == f"{NAME}.{field}"
