"""RosTimer counts the launch's ROS clock: after SetUseSimTime(True), simulated time from /clock."""

from __future__ import annotations

import sys

import pytest

from diffctl.launch.actions import ExecuteProcess, OpaqueFunction, Shutdown
from diffctl.launch_ros.actions import RosTimer, SetUseSimTime
from diffctl.launch_ros.ros_adapters import get_ros_node

from .conftest import DATA, run


@pytest.mark.slow
def test_a_ros_timer_fires_on_simulated_time(router: str) -> None:
    fired_at_ns: list[int] = []

    def record(context) -> None:
        fired_at_ns.append(get_ros_node(context).get_clock().now().nanoseconds)

    code, _ = run([
        ExecuteProcess(cmd=[sys.executable, str(DATA / "clock.py")]),  # 10 s of sim time every 20 ms
        SetUseSimTime(True),
        RosTimer(period=60.0, actions=[OpaqueFunction(function=record), Shutdown(reason="timer")]),
    ])  # fmt: skip
    assert code == 0
    assert len(fired_at_ns) == 1
    assert 60e9 <= fired_at_ns[0] < 600e9  # simulated seconds: the wall clock is near 1.8e18 ns
