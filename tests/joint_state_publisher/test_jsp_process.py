"""`diffctl joint-state-publisher` as a real process on a real router: it takes /robot_description,
publishes joint_states at `rate`, and lets a source_list topic set the free joints."""

from __future__ import annotations

import threading
from typing import Any

import pytest

from tests.joint_state_publisher.test_joints import ARM
from tests.probe import Probe
from tests.waiting import wait_for


def test_publishes_the_description_joints_and_merges_sources(router: str, procs) -> None:
    jsp = procs.diffctl(
        "joint-state-publisher", "--ros-args", "-p", "rate:=50", "-p", "source_list:=[/arm_feedback]"
    )
    node = Probe("jsp_probe")
    try:
        got: list[Any] = []
        lock = threading.Lock()

        def keep(msg: Any) -> None:
            with lock:
                got.append(msg)

        node.create_subscription("/joint_states", "sensor_msgs/msg/JointState", keep)
        desc = node.create_publisher("/robot_description", "std_msgs/msg/String", latched=True)
        desc.publish({"data": ARM})
        assert wait_for(lambda: len(got) >= 3, timeout_s=30), (procs.stop(jsp), jsp.stdout.read())
        last = got[-1]
        assert list(last.name) == ["wheel", "shoulder", "lift", "finger", "tip"]
        assert list(last.position) == pytest.approx([0.0, 0.0, 0.4, 0.9, -0.4])

        feedback = node.create_publisher("/arm_feedback", "sensor_msgs/msg/JointState")
        assert wait_for(lambda: feedback.subscription_count > 0, timeout_s=30)

        def moved() -> bool:
            with lock:
                return bool(got) and list(got[-1].position)[2] == pytest.approx(0.5)

        assert wait_for(moved, timeout_s=30, every=lambda: feedback.publish({"name": ["lift"], "position": [0.5]}))
        assert list(got[-1].position) == pytest.approx([0.0, 0.0, 0.5, 1.1, -0.6])
    finally:
        node.close()
    assert procs.stop(jsp) == 0


def test_a_bad_description_file_starts_nothing(procs, tmp_path) -> None:
    bad = tmp_path / "robot.urdf"
    bad.write_text('<robot name="r"><joint name="j" type="revolute"></joint></robot>')
    p = procs.diffctl("joint-state-publisher", str(bad))
    out = p.stdout.read()
    assert p.wait(60) == 2
    assert out.strip().splitlines() == [f"error: {bad}:1: joint 'j' of type 'revolute' has no <limit>"]
