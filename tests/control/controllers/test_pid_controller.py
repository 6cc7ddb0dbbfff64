"""pid_controller driven directly (a real client node), with the parameter files and expected commands of upstream's
test_pid_controller.cpp (ros2_controllers jazzy): state 1.1, reference 101.101, dt 0.01 s, gains p 1, i 2, d 3 with
antiwindup "none" → 30100.301; chained reference 5 → 1173.9; 10 with angle_wraparound → 787.6612219; feed-forward
gain 1 with p 0.5 → 6.95; the integral kept across a restart with save_i_term → 2.00002."""

from __future__ import annotations

import math

import pytest
from controller_harness import START_NS, activate, configure, hand_interfaces, make_controller, update

from diffctl.control.controllers.pid_controller import PidController
from diffctl.control.lifecycle import State
from diffctl.errors import ParameterError

pytestmark = pytest.mark.usefixtures("client_bus")

NAME = "test_pid_controller"
BASE = {"dof_names": ["joint1"], "command_interface": "position", "reference_and_state_interfaces": ["position"],
        "set_current_state_as_first_setpoint": True, "gains.joint1.antiwindup_strategy": "none"}
UNLIMITED = {**BASE, "gains.joint1.p": 1.0, "gains.joint1.i": 2.0, "gains.joint1.d": 3.0}


def running(params, chained=False, states=(1.1,)):
    c = make_controller(PidController, NAME, params)
    configure(c)
    cmd, state = hand_interfaces(c)
    for h, x in zip(state.values(), states, strict=False):
        h.value = x
    for h in cmd.values():
        h.value = 101.101
    if chained:
        c.set_chained_mode(True)
    activate(c)
    return c, list(cmd.values()), list(state.values())


def test_interfaces_exported_as_upstream() -> None:
    c, _, _ = running({**UNLIMITED, "reference_and_state_interfaces": ["position", "velocity"],
                       "dof_names": ["joint1", "joint2"], "command_interface": "velocity"}, states=(1.1, 2.2))
    assert c.command_interface_configuration().names == ["joint1/velocity", "joint2/velocity"]
    assert c.state_interface_configuration().names == ["joint1/position", "joint2/position", "joint1/velocity",
                                                       "joint2/velocity"]
    assert [r.name for r in c.reference_interfaces] == [f"{NAME}/joint1/position", f"{NAME}/joint2/position",
                                                        f"{NAME}/joint1/velocity", f"{NAME}/joint2/velocity"]
    assert [s.name for s in c.exported_state_interfaces] == [r.name for r in c.reference_interfaces]
    # test_activate_set_current_state_as_first_setpoint_true: the references start at the measured state
    assert [r.value for r in c.reference_interfaces[:2]] == [1.1, 2.2]


def test_commands_as_upstream() -> None:
    # test_update_logic_feedforward_off: a reference through ~/reference, used once
    c, cmd, _ = running(UNLIMITED)
    c.probe.deliver(f"/{NAME}/reference", {"dof_names": ["joint1"], "values": [101.101], "values_dot": [0.0]})
    update(c, START_NS, 0.01)
    assert round(cmd[0].value * 1e5) / 1e5 == pytest.approx(30100.301, abs=1e-5)
    assert math.isnan(c._reference[0][0])
    state = c.probe.sent(f"/{NAME}/controller_state")[-1]["dof_states"][0]
    assert (state["name"], state["reference"], state["feedback"], state["time_step"]) == ("joint1", 101.101, 1.1, 0.01)
    assert state["error"] == pytest.approx(100.001) and state["output"] == cmd[0].value
    # test_update_logic_chainable_not_use_subscriber_update: chained, the topic ignored
    c, cmd, _ = running(UNLIMITED, chained=True)
    c.reference_interfaces[0].value = 5.0
    c.probe.deliver(f"/{NAME}/reference", {"dof_names": ["joint1"], "values": [10.0], "values_dot": [0.0]})
    update(c, START_NS, 0.01)
    assert cmd[0].value == pytest.approx(1173.9)
    # test_update_logic_angle_wraparound_on
    c, cmd, _ = running({**UNLIMITED, "gains.joint1.angle_wraparound": True}, chained=True)
    c.reference_interfaces[0].value = 10.0
    update(c, START_NS, 0.01)
    assert cmd[0].value == pytest.approx(787.6612219, abs=1e-5)
    # test_update_chained_feedforward_with_gain and _off_with_gain
    ff = {**BASE, "gains.joint1.p": 0.5, "gains.joint1.feedforward_gain": 1.0}
    for enabled, expected in ((True, 6.95), (False, 1.95)):
        c, cmd, _ = running({**ff, "enable_feedforward": enabled}, chained=True)
        c.reference_interfaces[0].value = 5.0
        update(c, START_NS, 0.01)
        assert cmd[0].value == pytest.approx(expected)


@pytest.mark.parametrize(("save", "after"), [(False, 0.0), (True, 2.00002)])
def test_integral_across_a_restart(save, after) -> None:
    # test_save_i_term_off / _on
    c, cmd, _ = running({**UNLIMITED, "gains.joint1.save_i_term": save})
    c.probe.deliver(f"/{NAME}/reference", {"values": [101.101]})
    assert "does not have DoF names defined" in c.probe.log.text("WARN")
    update(c, START_NS, 0.01)
    c.on_deactivate(State.ACTIVE)
    activate(c)
    c.probe.deliver(f"/{NAME}/reference", {"dof_names": ["joint1"], "values": [1.1]})
    update(c, START_NS, 0.01)
    assert round(cmd[0].value * 1e5) / 1e5 == pytest.approx(after, abs=1e-5)


def test_feedforward_service_gains_at_runtime_and_bad_input() -> None:
    from diffctl.client.interfaces import cls
    from diffctl.client.parameter import Parameter

    c, cmd, _ = running({**BASE, "gains.joint1.p": 0.5, "gains.joint1.feedforward_gain": 1.0}, chained=True)
    srv = cls("std_srvs/srv/SetBool")
    c.get_node().set_parameters([Parameter("gains.joint1.p", value=1.0)])
    c.reference_interfaces[0].value = 5.0
    update(c, START_NS, 0.01)
    assert cmd[0].value == pytest.approx(3.9)  # the new gain; feed-forward as enable_feedforward says (off)
    assert c._on_set_feedforward(srv.Request(data=True), srv.Response()).success
    update(c, START_NS, 0.01)
    assert cmd[0].value == pytest.approx(3.9 + 5.0)
    refused = c.get_node().set_parameters([Parameter("gains.joint1.i_clamp_min", value=1.0)])[0]
    assert not refused.successful and "i_min to be smaller or equal to 0 (i_min: 1)" in refused.reason
    c.probe.deliver(f"/{NAME}/reference", {"dof_names": ["a", "b"], "values": [1.0, 2.0]})
    assert "Size of input data names (2) and/or values (2) is not matching the expected size (1)." in \
        c.probe.log.text("ERROR")
    with pytest.raises(ParameterError) as e:
        make_controller(PidController, NAME, {**BASE, "gains.joint1.antiwindup_strategy": "clamp"})
    assert e.value.field == f"{NAME}.gains.joint1.antiwindup_strategy"
