"""Controllers publishing through a message template give exactly what serializing their message gives: the
template itself against the client's serializer, and every sample a running controller hands to the publishing
thread, packed only after the run (what was handed over must not change later), is the serializer's own bytes
for what it decodes to."""

from __future__ import annotations

import math
import random

import pytest
from controller_harness import NS, activate, configure, hand_interfaces, make_controller, update

from diffctl.client.interfaces import cls, deserialize, serialize
from diffctl.control.cdr_template import CdrTemplate, TemplateError
from diffctl.control.controller_interface import StateInterface
from diffctl.control.controllers.diff_drive import DiffDriveController
from diffctl.control.controllers.joint_state_broadcaster import JointStateBroadcaster

pytestmark = pytest.mark.usefixtures("client_bus")
ODOMETRY = "nav_msgs/msg/Odometry"
STAMP = [("header.stamp.sec", "i"), ("header.stamp.nanosec", "I")]


def test_a_template_packs_what_the_serializer_writes() -> None:
    msg = cls(ODOMETRY)()
    msg.header.frame_id, msg.child_frame_id = "odom", "base_footprint"
    for i in range(6):
        msg.pose.covariance[7 * i] = 0.001 * (i + 1)
    paths = ["pose.pose.position.x", "pose.pose.position.y", "pose.pose.orientation.z", "pose.pose.orientation.w",
             "twist.twist.linear.x", "twist.twist.angular.z"]  # fmt: skip
    template = CdrTemplate(msg, ODOMETRY, STAMP + [(p, "d") for p in paths])
    rng = random.Random(7)
    for _ in range(200):
        values = [rng.randrange(2**31), rng.randrange(10**9)]
        values += [rng.choice([rng.uniform(-1e3, 1e3), -0.0, math.nan, math.inf]) for _ in paths]
        msg.header.stamp.sec, msg.header.stamp.nanosec = values[:2]
        for p, v in zip(paths, values[2:], strict=True):
            parent, _, leaf = p.rpartition(".")
            obj = msg
            for part in parent.split("."):
                obj = getattr(obj, part)
            setattr(obj, leaf, v)
        assert template.encode(values) == serialize(msg)


def test_a_template_whose_leaf_is_not_what_it_claims_is_refused() -> None:
    msg = cls(ODOMETRY)()
    with pytest.raises(TemplateError):
        CdrTemplate(msg, ODOMETRY, [("header.stamp.sec", "d")])  # an int32, not a float64
    with pytest.raises(TemplateError):
        CdrTemplate(msg, ODOMETRY, [("pose.pose.position.y", "d"), ("pose.pose.position.x", "d")])  # out of order


def _packets_are_canonical(c) -> dict[str, int]:
    """Every sample recorded: the bytes re-serialize to themselves; the count per topic."""
    counts = {}
    for publisher, raw in c.probe.recorder.raw:
        assert serialize(deserialize(raw, publisher.msg_type)) == raw
        counts[publisher.topic_name] = counts.get(publisher.topic_name, 0) + 1
    return counts


@pytest.mark.parametrize("params", [{}, {"publish_limited_velocity": True, "enable_odom_tf": False},
                                    {"open_loop": False, "position_feedback": False}])  # fmt: skip
def test_diff_drive_hands_over_what_the_serializer_writes(params: dict) -> None:
    base = {"left_wheel_names": ["l"], "right_wheel_names": ["r"], "wheel_separation": 0.3, "wheel_radius": 0.04,
            "publish_rate": 50.0, "pose_covariance_diagonal": [0.001, 0.001, 0.0, 0.0, 0.0, 0.01],
            **params}  # fmt: skip
    c = make_controller(DiffDriveController, "dd", base)
    configure(c)
    cmd, state = hand_interfaces(c)
    activate(c)
    t = c.probe.time_ns
    for k in range(120):
        if k % 10 == 0:
            sec, nanosec = divmod(t, NS)
            c.probe.deliver("/dd/cmd_vel", {"header": {"stamp": {"sec": sec, "nanosec": nanosec}},
                                           "twist": {"linear": {"x": 0.4}, "angular": {"z": -0.7}}})  # fmt: skip
        update(c, t, 0.01)
        for name, s in state.items():  # the wheels follow their commands
            s.value = cmd[f"{name.split('/')[0]}/velocity"].value
        t += 10_000_000
        c.probe.time_ns = t
    counts = _packets_are_canonical(c)
    assert counts and all(n > 10 for n in counts.values())


def test_joint_state_broadcaster_hands_over_what_the_serializer_writes() -> None:
    hw = {"b/position": 1.5, "b/velocity": 2.0, "imu/orientation.x": 0.1, "a/position": -0.5, "a/effort": 3.0}
    c = make_controller(JointStateBroadcaster, "jsb", {"extra_joints": ["x"]})
    configure(c)
    handles = [StateInterface(n, v) for n, v in hw.items()]
    c.state_interfaces, c.command_interfaces = handles, []
    activate(c)
    for k in range(5):
        for i, h in enumerate(handles):
            h.value = math.nan if (k + i) % 4 == 0 else k * 0.5 - i
        update(c, 100 * NS + k * 10_000_000, 0.01)
    assert sorted(_packets_are_canonical(c).values()) == [5, 5]
