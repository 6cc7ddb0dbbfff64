"""JointStateBroadcaster driven directly (a real client node): claimed interfaces, /joint_states and
/dynamic_joint_states content, joint order and filtering by the robot description, extra joints, interface
mapping, local topics."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from controller_harness import NS, activate, configure, hand_interfaces, make_controller, update

from diffctl.control.controller_interface import StateInterface
from diffctl.control.controllers.joint_state_broadcaster import JointStateBroadcaster
from diffctl.errors import ParameterError, RuntimeFailure

pytestmark = pytest.mark.usefixtures("client_bus")

REPO = Path(__file__).resolve().parents[3]
NAME = "joint_state_broadcaster"
HW = {
    "base_link_to_left_wheel/position": 1.5,
    "base_link_to_left_wheel/velocity": 2.0,
    "imu_sensor/orientation.x": 0.1,
    "base_link_to_right_wheel/position": -0.5,
    "base_link_to_right_wheel/velocity": 3.0,
}


def broadcaster(params: dict | None = None, hw: dict[str, float] | None = None, description: str = ""):
    c = make_controller(JointStateBroadcaster, NAME, params or {}, robot_description=description)
    configure(c)
    c.state_interfaces = [StateInterface(n, v) for n, v in (hw or HW).items()]  # "all": what the hardware has
    c.command_interfaces = []
    activate(c)
    return c


def test_claims_nothing_to_command_and_all_or_the_cross_product_of_states():
    c = make_controller(JointStateBroadcaster, NAME, {})
    assert c.command_interface_configuration().type == "none"
    assert c.state_interface_configuration().type == "all"
    c = make_controller(JointStateBroadcaster, NAME, {"joints": ["a", "b"], "interfaces": ["position", "effort"]})
    assert c.state_interface_configuration().names == ["a/position", "a/effort", "b/position", "b/effort"]
    c = make_controller(JointStateBroadcaster, NAME, {"joints": ["a"]})
    assert c.state_interface_configuration().type == "all"
    assert "both 'joints' and 'interfaces' are needed" in c.probe.log.text("WARN")


def test_joint_states_content_with_nan_for_missing_interfaces():
    c = broadcaster()
    update(c, 12 * NS + 34, 0.01)
    js = c.probe.sent("/joint_states")[-1]
    assert js["name"] == ["base_link_to_left_wheel", "base_link_to_right_wheel"]  # the IMU is not a joint state
    assert js["position"] == [1.5, -0.5] and js["velocity"] == [2.0, 3.0]
    assert all(math.isnan(e) for e in js["effort"])
    assert js["header"]["stamp"] == {"sec": 12, "nanosec": 34} and js["header"]["frame_id"] == "base_link"
    djs = c.probe.sent("/dynamic_joint_states")[-1]
    assert djs["joint_names"] == ["base_link_to_left_wheel", "imu_sensor", "base_link_to_right_wheel"]
    assert djs["interface_values"][1] == {"interface_names": ["orientation.x"], "values": [0.1]}


def test_values_follow_the_hardware_every_update():
    c = broadcaster()
    handle = next(si for si in c.state_interfaces if si.name == "base_link_to_right_wheel/velocity")
    for v in (0.0, 4.25):
        handle.value = v
        update(c, NS, 0.01)
        assert c.probe.sent("/joint_states")[-1]["velocity"][1] == v
        assert c.probe.sent("/dynamic_joint_states")[-1]["interface_values"][2]["values"][1] == v
    assert len(c.probe.sent("/joint_states")) == 2


def test_description_orders_and_filters_joints():
    sdf = (REPO / "description" / "my_diff_car_control.sdf").read_text()
    hw = {
        "gpio/flag": 1.0,
        "base_link_to_right_wheel/position": 2.0,
        "base_link_to_left_wheel/position": 1.0,
        "not_in_model/position": 7.0,
    }
    c = broadcaster(hw=hw, description=sdf)
    update(c, NS, 0.01)
    assert c.probe.sent("/joint_states")[-1]["name"] == ["base_link_to_left_wheel", "base_link_to_right_wheel"]
    c = broadcaster({"use_urdf_to_filter": False}, hw=hw, description=sdf)
    update(c, NS, 0.01)
    assert c.probe.sent("/joint_states")[-1]["name"] == [
        "base_link_to_right_wheel",
        "base_link_to_left_wheel",
        "not_in_model",
    ]


def test_joints_param_sets_the_order():
    hw = {"a/position": 1.0, "b/position": 2.0}
    c = broadcaster({"joints": ["b", "a"], "interfaces": ["position"]}, hw=hw)
    update(c, NS, 0.01)
    assert c.probe.sent("/joint_states")[-1]["name"] == ["b", "a"]
    assert c.probe.sent("/joint_states")[-1]["position"] == [2.0, 1.0]


def test_extra_joints_mapping_local_topics_and_frame_id():
    hw = {"wheel/angle": 0.7, "wheel/velocity": 1.0}
    params = {
        "extra_joints": ["caster"],
        "map_interface_to_joint_state.position": "angle",
        "use_local_topics": True,
        "frame_id": "chassis",
        "publish_dynamic_joint_states": False,
    }
    c = broadcaster(params, hw=hw)
    update(c, NS, 0.01)
    js = c.probe.sent(f"/{NAME}/joint_states")[-1]
    assert js["name"] == ["wheel", "caster"]
    assert js["position"] == [0.7, 0.0] and js["velocity"] == [1.0, 0.0] and js["effort"][1] == 0.0
    assert js["header"]["frame_id"] == "chassis"
    assert "/joint_states" not in c.probe.publishers and f"/{NAME}/dynamic_joint_states" not in c.probe.publishers


def test_no_state_interfaces_fails_activation():
    c = make_controller(JointStateBroadcaster, NAME, {})
    configure(c)
    hand_interfaces(c)
    with pytest.raises(RuntimeFailure, match="None of the requested interfaces exist"):
        activate(c)


@pytest.mark.parametrize(
    ("params", "field"),
    [
        ({"joints": "left"}, "joints"),
        ({"use_local_topics": "yes"}, "use_local_topics"),
        ({"map_interface_to_joint_state.effort": "position"}, "map_interface_to_joint_state"),
    ],
)
def test_bad_parameters(params, field):
    with pytest.raises(ParameterError) as e:
        make_controller(JointStateBroadcaster, NAME, params)
    assert e.value.field == f"{NAME}.{field}"
