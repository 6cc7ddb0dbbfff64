"""joint_state_publisher's reading of URDF and SDF joints and the state it publishes (pure parts)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from diffctl.errors import DescriptionError, ParameterError
from diffctl.joint_state_publisher.joints import parse_joints
from diffctl.joint_state_publisher.params import JspParams
from diffctl.joint_state_publisher.state import JointStates

REPO = Path(__file__).resolve().parents[2]

ARM = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="l4"/><link name="l5"/>
  <link name="l6"/><link name="l7"/>
  <joint name="fixed_j" type="fixed"><parent link="base"/><child link="l1"/></joint>
  <joint name="wheel" type="continuous"><parent link="base"/><child link="l2"/></joint>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="l3"/>
    <limit lower="-1.0" upper="2.0" effort="1" velocity="1"/>
    <safety_controller soft_lower_limit="-0.5" soft_upper_limit="1.5" k_velocity="1"/></joint>
  <joint name="lift" type="prismatic"><parent link="base"/><child link="l4"/>
    <limit lower="0.2" upper="0.6" effort="1" velocity="1"/></joint>
  <joint name="finger" type="prismatic"><parent link="base"/><child link="l5"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/><mimic joint="lift" multiplier="2" offset="0.1"/></joint>
  <joint name="tip" type="prismatic"><parent link="base"/><child link="l6"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/><mimic joint="finger" multiplier="-1" offset="0.5"/></joint>
  <joint name="float" type="floating"><parent link="base"/><child link="l7"/></joint>
</robot>
"""


def test_urdf_free_and_mimic_joints_with_their_defaults() -> None:
    joints = parse_joints(ARM, JspParams())
    assert joints.order == ("wheel", "shoulder", "lift", "finger", "tip")
    assert (joints.free["wheel"].min_rad, joints.free["wheel"].max_rad) == (-math.pi, math.pi)
    assert (joints.free["shoulder"].min_rad, joints.free["shoulder"].max_rad) == (-0.5, 1.5)  # safety limits
    assert joints.free["lift"].zero == pytest.approx(0.4)  # 0 is outside [0.2, 0.6]: the middle
    msg = JointStates(joints, JspParams()).message()
    assert msg is not None
    assert msg["name"] == ["wheel", "shoulder", "lift", "finger", "tip"]
    # finger = 2·lift + 0.1; tip = −finger + 0.5 = −2·lift + 0.4 (a chain)
    assert msg["position"] == pytest.approx([0.0, 0.0, 0.4, 0.9, -0.4])
    assert msg["velocity"] == [] and msg["effort"] == []


def test_parameters_zeros_mimic_off_limits_off_and_defaults() -> None:
    params = JspParams.from_dict(
        {
            "zeros": {"shoulder": 1.2},
            "use_mimic_tags": False,
            "use_smallest_joint_limits": "false",
            "publish_default_velocities": True,
        }
    )
    joints = parse_joints(ARM, params)
    assert set(joints.free) == {"wheel", "shoulder", "lift", "finger", "tip"}
    assert joints.free["shoulder"].max_rad == 2.0
    msg = JointStates(joints, params).message()
    assert msg is not None
    assert msg["position"][1] == 1.2
    assert msg["velocity"] == [0.0] * 5


def test_source_list_values_win_and_dependents_follow() -> None:
    states = JointStates(parse_joints(ARM, JspParams()), JspParams())
    states.merge(["lift", "unknown", "wheel"], [0.5, 9.0, 3.0], [1.0, 2.0, 0.25], [])
    msg = states.message()
    assert msg is not None
    assert msg["position"] == pytest.approx([3.0, 0.0, 0.5, 1.1, -0.6])
    assert msg["velocity"] == pytest.approx([0.25, 0.0, 1.0, 2.0, -2.0])


def test_delta_sweeps_bounce_at_limits_and_wrap_continuous_joints() -> None:
    params = JspParams.from_dict({"delta": 1.0})
    states = JointStates(parse_joints(ARM, params), params)
    for _ in range(4):
        states.sweep(1.0)
    msg = states.message()
    assert msg is not None
    wheel, shoulder = msg["position"][0], msg["position"][1]
    assert wheel == pytest.approx(-math.pi)  # 0, 1, 2, 3, then past +π: wrapped to −π
    assert shoulder == pytest.approx(1.5 - 2.0)  # reached 1.5, came back twice


def test_the_projects_sdf_car_publishes_its_two_wheels() -> None:
    text = (REPO / "description" / "my_diff_car.sdf").read_text()
    joints = parse_joints(text, JspParams())
    assert joints.order == ("base_link_to_left_wheel", "base_link_to_right_wheel")
    assert all(j.continuous for j in joints.free.values())


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('<robot name="r"><joint name="j" type="revolute"><parent link="a"/><child link="b"/></joint></robot>',
         "has no <limit>"),
        ('<robot name="r"><joint name="j" type="prismatic"><limit upper="1"/></joint></robot>', 'no "lower" limit'),
        ('<robot name="r"><joint name="j" type="prismatic"><limit lower="x" upper="1"/></joint></robot>',
         "must be a number"),
        ('<robot name="r"><joint name="a" type="continuous"><mimic joint="b"/></joint>'
         '<joint name="b" type="continuous"><mimic joint="a"/></joint></robot>', "mimic joints form a cycle"),
        ('<robot name="r"><joint name="a" type="continuous"><mimic joint="nope"/></joint></robot>',
         "mimics 'nope', which is not a free joint"),
        ("<robot", "malformed XML"),
        ("<world/>", "neither <robot> (URDF) nor <sdf>"),
    ],
)
def test_unusable_descriptions_are_one_error(text: str, message: str) -> None:
    with pytest.raises(DescriptionError, match=None) as e:
        parse_joints(text, JspParams(), "robot.urdf")
    assert message in str(e.value)
    assert str(e.value).startswith("robot.urdf")


@pytest.mark.parametrize(
    ("params", "field"),
    [
        ({"rate": 0}, "rate"),
        ({"rate": 2.5}, "rate"),
        ({"source_list": "joint_states"}, "source_list"),
        ({"zeros.j": "high"}, "zeros.j"),
        ({"delta": float("nan")}, "delta"),
        ({"dependent_joints.j.factor": 2.0}, "dependent_joints.j.parent"),
        ({"dependent_joints.j.gain": 2.0}, "dependent_joints.j.gain"),
        ({"use_mimic_tags": "maybe"}, "use_mimic_tags"),
    ],
)
def test_bad_parameters_name_the_parameter(params: dict, field: str) -> None:
    with pytest.raises(ParameterError) as e:
        JspParams.from_dict(params)
    assert e.value.field == field
    assert e.value.exit_code == 2
