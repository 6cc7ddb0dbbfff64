"""The /joint_states rules (rate limit per joint, time going back, bad positions) without a bus.

`TfPublisher` is the node's pure part; the wire itself is covered by test_rsp_process.py.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from diffctl.client.interfaces import cls
from diffctl.description.sdf_loader import load_model
from diffctl.robot_state_publisher.node import TfPublisher

CAR = Path(__file__).resolve().parents[2] / "description" / "my_diff_car.sdf"
LEFT, RIGHT = "base_link_to_left_wheel", "base_link_to_right_wheel"
MS = 1_000_000


def joint_states(stamp_ns: int, names: list[str], positions: list[float]) -> Any:
    msg = cls("sensor_msgs/msg/JointState")(name=names, position=positions)
    msg.header.stamp.sec, msg.header.stamp.nanosec = stamp_ns // 10**9, stamp_ns % 10**9
    return msg


def stamps_ms(transforms: list[Any]) -> list[int]:
    return [t.header.stamp.sec * 1000 + t.header.stamp.nanosec // MS for t in transforms]


def test_rate_limit_per_joint_time_reset_and_zero_stamp() -> None:
    tf = TfPublisher(load_model(CAR), "", print)
    sent = []
    for t_ms in range(0, 200, 10):  # 100 Hz input, 20 Hz limit → one in five
        sent += tf.moved(joint_states(10**9 + t_ms * MS, [LEFT, RIGHT], [0.1, 0.2]), 777, 50 * MS, False)[:1]
    assert stamps_ms(sent) == [1000, 1050, 1100, 1150]
    # a sim reset sends time backwards: publish at once instead of waiting for the old clock
    assert tf.moved(joint_states(5 * MS, [LEFT, RIGHT], [0.0, 0.0]), 777, 50 * MS, False)
    # a zero stamp means "now" on this node's clock, and ignore_timestamp lifts the rate limit
    again = [tf.moved(joint_states(0, [LEFT], [1.0]), 777, 50 * MS, True)[0] for _ in range(2)]
    assert [(t.header.stamp.sec, t.header.stamp.nanosec) for t in again] == [(0, 777)] * 2


def test_bad_joint_states_are_skipped_with_one_warning_and_frames_get_the_prefix() -> None:
    warnings: list[str] = []
    tf = TfPublisher(load_model(CAR), "car/", warnings.append)
    assert tf.moved(joint_states(1, [LEFT, RIGHT], [0.5]), 0, 0, False) == []
    assert tf.moved(joint_states(2, [LEFT, RIGHT], [0.5]), 0, 0, False) == []
    out = [tf.moved(joint_states(3, [LEFT, RIGHT], [math.nan, 0.5]), 0, 0, False),
           tf.moved(joint_states(4, [LEFT, RIGHT], [math.inf, 0.5]), 0, 0, False)]
    assert [[t.child_frame_id for t in m] for m in out] == [["car/right_wheel"], ["car/right_wheel"]]
    assert len(warnings) == 2, warnings
    # the fixed transforms, with the root at base_footprint
    assert {t.header.frame_id for t in tf.fixed(0)} == {"car/base_footprint", "car/base_link"}


def test_the_nodes_reused_message_is_byte_for_byte_a_fresh_one() -> None:
    from diffctl.client.interfaces import serialize

    fresh, reused = TfPublisher(load_model(CAR), "car/", print), TfPublisher(load_model(CAR), "car/", print)
    samples = [([LEFT, RIGHT], [0.1 * i, -0.3 * i]) for i in range(4)] + [([RIGHT], [2.0]), ([LEFT, RIGHT], [1.0, 0.5])]
    for i, (names, positions) in enumerate(samples):
        stamp = 10**9 + i * 60 * MS
        want = fresh.moved(joint_states(stamp, names, positions), 0, 50 * MS, False)
        got = reused.moved_message(joint_states(stamp, names, positions), 0, 50 * MS, False)
        assert got is not None
        assert serialize(got) == serialize(cls("tf2_msgs/msg/TFMessage")(transforms=want))
    # rate limited: nothing to send
    assert reused.moved_message(joint_states(stamp + MS, [LEFT], [0.0]), 0, 50 * MS, False) is None
