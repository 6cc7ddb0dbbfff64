"""The /joint_states callback's rules (rate limit per joint, time going back, bad positions) without a bus.

The node here only records what is published; the wire itself is covered by test_rsp_process.py.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from diffctl.description.sdf_loader import load_model
from diffctl.interfaces import types
from diffctl.robot_state_publisher.node import RobotStatePublisher, RspParams

CAR = Path(__file__).resolve().parents[2] / "description" / "my_diff_car.sdf"
LEFT, RIGHT = "base_link_to_left_wheel", "base_link_to_right_wheel"


class Recorder:
    def __init__(self, topic: str) -> None:
        self.topic, self.sent = topic, []

    def publish(self, msg: Any) -> None:
        self.sent.append(msg if isinstance(msg, dict) else types.to_dict(msg))


class Log:
    def __init__(self) -> None:
        self.lines: list[str] = []

    def info(self, text: str) -> None:
        self.lines.append(text)

    warn = info


class RecordingNode:
    def __init__(self) -> None:
        self.pubs: dict[str, Recorder] = {}
        self.log = Log()

    def create_publisher(self, topic: str, typename: str, **_: Any) -> Recorder:
        return self.pubs.setdefault(topic, Recorder(topic))

    def create_subscription(self, *_: Any, **__: Any) -> None:
        return None

    def now_ns(self) -> int:
        return 777


def joint_states(stamp_ns: int, names: list[str], positions: list[float]) -> Any:
    return types.new(
        "sensor_msgs/msg/JointState",
        {
            "header": {"stamp": {"sec": stamp_ns // 10**9, "nanosec": stamp_ns % 10**9}},
            "name": names,
            "position": positions,
        },
    )


def make(**params: Any) -> tuple[RobotStatePublisher, RecordingNode]:
    node = RecordingNode()
    p = RspParams.from_dict({"robot_description": CAR.read_text(), **params})
    return RobotStatePublisher(node, p, load_model(CAR)), node


def test_rate_limit_per_joint_time_reset_and_zero_stamp() -> None:
    rsp, node = make(publish_frequency=20.0)
    tf = node.pubs["/tf"].sent
    ms = 1_000_000
    for t_ms in range(0, 200, 10):  # 100 Hz input, 20 Hz limit → one in five
        rsp.on_joint_states(joint_states(10**9 + t_ms * ms, [LEFT, RIGHT], [0.1, 0.2]))
    assert len(tf) == 4
    assert [m["transforms"][0]["header"]["stamp"]["nanosec"] // ms for m in tf] == [0, 50, 100, 150]
    # a sim reset sends time backwards: publish at once instead of waiting for the old clock
    rsp.on_joint_states(joint_states(5 * ms, [LEFT, RIGHT], [0.0, 0.0]))
    assert len(tf) == 5
    # a zero stamp means "now" on this node's clock
    rsp2, node2 = make(ignore_timestamp=True)
    rsp2.on_joint_states(joint_states(0, [LEFT], [1.0]))
    rsp2.on_joint_states(joint_states(0, [LEFT], [1.0]))
    stamps = [m["transforms"][0]["header"]["stamp"] for m in node2.pubs["/tf"].sent]
    assert stamps == [{"sec": 0, "nanosec": 777}] * 2  # and ignore_timestamp lifts the rate limit


def test_bad_joint_states_are_skipped_with_one_warning() -> None:
    rsp, node = make(publish_frequency=0.0)
    tf = node.pubs["/tf"].sent
    rsp.on_joint_states(joint_states(1, [LEFT, RIGHT], [0.5]))
    rsp.on_joint_states(joint_states(2, [LEFT, RIGHT], [0.5]))
    assert tf == []
    rsp.on_joint_states(joint_states(3, [LEFT, RIGHT], [math.nan, 0.5]))
    rsp.on_joint_states(joint_states(4, [LEFT, RIGHT], [math.inf, 0.5]))
    assert [[t["child_frame_id"] for t in m["transforms"]] for m in tf] == [["right_wheel"], ["right_wheel"]]
    warnings = [line for line in node.log.lines if "names but" in line or "position is" in line]
    assert len(warnings) == 2, node.log.lines
    # static transforms went out once, latched, with the root at base_footprint
    (static,) = node.pubs["/tf_static"].sent
    assert {t["header"]["frame_id"] for t in static["transforms"]} == {"base_footprint", "base_link"}
    assert node.pubs["robot_description"].sent == [{"data": CAR.read_text()}]
