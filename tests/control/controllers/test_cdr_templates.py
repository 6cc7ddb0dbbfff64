"""Controllers publishing through a message template give exactly what serializing their message gives:
the template itself against the bus serializer, and each controller run twice on the same inputs, once
through a publisher that takes messages and once through one that takes a template's values (as the
controllers' RealtimePublisher does), packed only after the run: what was handed over must not change later."""

from __future__ import annotations

import math
import random

import pytest
from controller_fakes import NS, FakeNode, hand_interfaces

from diffctl.control.cdr_template import CdrTemplate, TemplateError
from diffctl.control.controller_interface import StateInterface
from diffctl.control.controllers.diff_drive import DiffDriveController
from diffctl.control.controllers.joint_state_broadcaster import JointStateBroadcaster
from diffctl.interfaces import types

ODOMETRY = "nav_msgs/msg/Odometry"
STAMP = [("header.stamp.sec", "i"), ("header.stamp.nanosec", "I")]


def test_a_template_packs_what_the_serializer_writes() -> None:
    msg = types.new(ODOMETRY, {"header": {"frame_id": "odom"}, "child_frame_id": "base_footprint"})
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
        assert template.encode(values) == types.serialize(msg, ODOMETRY)


def test_a_template_whose_leaf_is_not_what_it_claims_is_refused() -> None:
    msg = types.new(ODOMETRY, {})
    with pytest.raises(TemplateError):
        CdrTemplate(msg, ODOMETRY, [("header.stamp.sec", "d")])  # an int32, not a float64
    with pytest.raises(TemplateError):
        CdrTemplate(msg, ODOMETRY, [("pose.pose.position.y", "d"), ("pose.pose.position.x", "d")])  # out of order


class MessageOut:
    """Takes messages: serializes them as the bus publisher would."""

    def __init__(self, topic: str, type_name: str) -> None:
        self.topic, self.type_name, self.sent = topic, type_name, []

    def publish(self, msg: object) -> None:
        self.sent.append(types.serialize(msg, self.type_name))

    def packets(self) -> list[bytes]:
        return self.sent

    def close(self) -> None:
        pass


class ValuesOut(MessageOut):
    """Also takes a template's values, as the controllers' RealtimePublisher does (packed when asked)."""

    def publish_values(self, template: CdrTemplate, values: list | tuple) -> None:
        self.sent.append((template, values))

    def packets(self) -> list[bytes]:
        return [template.encode(values) for template, values in self.sent]


class Node(FakeNode):
    def __init__(self, name: str, params: dict, out: type[MessageOut]) -> None:
        super().__init__(name, params)
        self.out = out

    def create_publisher(self, topic: str, type_name: str, latched: bool = False, depth: int = 10) -> MessageOut:
        pub = self.out(self.resolve(topic), type_name)
        self.publishers[pub.topic] = pub  # type: ignore[assignment]
        return pub


def _controller(cls: type, name: str, params: dict, out: type[MessageOut]):
    c = cls()
    c.name = name
    c.node = Node(name, params, out)
    c.on_init()
    return c


def _sent(c) -> dict[str, list[bytes]]:
    return {topic: pub.packets() for topic, pub in c.node.publishers.items()}


@pytest.mark.parametrize("params", [{}, {"publish_limited_velocity": True, "enable_odom_tf": False},
                                    {"open_loop": False, "position_feedback": False}])  # fmt: skip
def test_diff_drive_publishes_the_same_bytes_either_way(params: dict) -> None:
    base = {"left_wheel_names": ["l"], "right_wheel_names": ["r"], "wheel_separation": 0.3, "wheel_radius": 0.04,
            "publish_rate": 50.0, "pose_covariance_diagonal": [0.001, 0.001, 0, 0, 0, 0.01], **params}  # fmt: skip
    runs = []
    for out in (MessageOut, ValuesOut):
        c = _controller(DiffDriveController, "dd", base, out)
        c.on_configure()
        assert (c._odom_cdr is not None) == (out is ValuesOut)
        cmd, state = hand_interfaces(c)
        c.on_activate()
        t = c.node.time_ns
        for k in range(120):
            if k % 10 == 0:
                sec, nanosec = divmod(t, NS)
                c.node.deliver("/dd/cmd_vel", {"header": {"stamp": {"sec": sec, "nanosec": nanosec}},
                                               "twist": {"linear": {"x": 0.4}, "angular": {"z": -0.7}}})  # fmt: skip
            c.update(t, 0.01)
            for name, s in state.items():  # the wheels follow their commands
                wheel = name.split("/")[0]
                s.value = cmd[f"{wheel}/velocity"].value
            t += 10_000_000
            c.node.time_ns = t
        runs.append(_sent(c))
    assert runs[0] == runs[1] and all(len(v) > 10 for v in runs[0].values())


def test_joint_state_broadcaster_publishes_the_same_bytes_either_way() -> None:
    hw = {"b/position": 1.5, "b/velocity": 2.0, "imu/orientation.x": 0.1, "a/position": -0.5, "a/effort": 3.0}
    runs = []
    for out in (MessageOut, ValuesOut):
        c = _controller(JointStateBroadcaster, "jsb", {"extra_joints": ["x"]}, out)
        c.on_configure()
        handles = [StateInterface(n, v) for n, v in hw.items()]
        c.state_interfaces, c.command_interfaces = handles, []
        c.on_activate()
        assert bool(c._fast) == (out is ValuesOut)
        for k in range(5):
            for i, h in enumerate(handles):
                h.value = math.nan if (k + i) % 4 == 0 else k * 0.5 - i
            c.update(100 * NS + k * 10_000_000, 0.01)
        runs.append(_sent(c))
    assert runs[0] == runs[1] and [len(v) for v in runs[0].values()] == [5, 5]
