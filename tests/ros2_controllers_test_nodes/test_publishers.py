"""ros2_controllers_test_nodes' publishers as ros2_control_demos start them, with the goal files of upstream's own
launch tests (rrbot_forward_position_publisher.yaml, rrbot_joint_trajectory_publisher.yaml; the period shortened):
the goals come round in order on the controllers' topics, a trajectory point per goal with time_from_start 4 s,
and check_starting_point holds the goals back until a joint state inside the limits arrives."""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any

import pytest

from tests.probe import Probe
from tests.waiting import wait_for

pytestmark = pytest.mark.slow

FORWARD = """publisher_forward_position_controller:
  ros__parameters:
    wait_sec_between_publish: 1
    publish_topic: "/forward_position_controller/commands"
    goal_names: ["pos1", "pos2", "pos3", "pos4"]
    pos1: [0.785, 0.785]
    pos2: [0.0, 0.0]
    pos3: [-0.785, -0.785]
    pos4: [0.0, 0.0]
"""
TRAJECTORY = """publisher_position_trajectory_controller:
  ros__parameters:
    controller_name: "joint_trajectory_position_controller"
    wait_sec_between_publish: 1
    goal_names: ["pos1", "pos2", "pos3", "pos4"]
    pos1:
      positions: [0.785, 0.785]
    pos2:
      positions: [0.0, 0.0]
    pos3:
      positions: [-0.785, -0.785]
    pos4:
      positions: [0.0, 0.0]
    joints:
      - joint1
      - joint2
    check_starting_point: true
    starting_point_limits:
      joint1: [-0.1,0.1]
      joint2: [-0.1,0.1]
"""
GOALS = [[0.785, 0.785], [0.0, 0.0], [-0.785, -0.785], [0.0, 0.0]]


def test_goals_cycle_on_the_controllers_topics(router: str, procs, tmp_path: Path) -> None:
    (tmp_path / "forward.yaml").write_text(FORWARD)
    (tmp_path / "trajectory.yaml").write_text(TRAJECTORY)
    node = Probe("goal_probe")
    got: dict[str, list[Any]] = {"forward": [], "trajectory": []}
    lock = threading.Lock()

    def keep(key: str):
        def on(m: Any) -> None:
            with lock:
                got[key].append(m)
        return on

    try:
        node.create_subscription("/forward_position_controller/commands", "std_msgs/msg/Float64MultiArray",
                                 keep("forward"))
        node.create_subscription("/joint_trajectory_position_controller/joint_trajectory",
                                 "trajectory_msgs/msg/JointTrajectory", keep("trajectory"))
        states = node.create_publisher("/joint_states", "sensor_msgs/msg/JointState")
        forward = procs.diffctl("run", "ros2_controllers_test_nodes", "publisher_forward_position_controller",
                                "--ros-args", "--params-file", str(tmp_path / "forward.yaml"))
        trajectory = procs.diffctl("run", "ros2_controllers_test_nodes", "publisher_joint_trajectory_controller",
                                   "--ros-args", "--params-file", str(tmp_path / "trajectory.yaml"))
        assert wait_for(lambda: len(got["forward"]) >= 5, timeout_s=90), (procs.stop(forward), forward.stdout.read())
        with lock:
            values = [list(m.data) for m in got["forward"]]
        # in order and round again (the first may pass before this probe's route to the publisher is up)
        assert any(values[:5] == [GOALS[(k + i) % 4] for i in range(5)] for k in range(4)), values

        # check_starting_point: nothing until a joint state inside ±0.1 arrives
        assert wait_for(lambda: states.subscription_count > 0, timeout_s=60)
        assert got["trajectory"] == []
        states.publish({"name": ["joint1", "joint2"], "position": [0.05, -0.05]})
        assert wait_for(lambda: len(got["trajectory"]) >= 4, timeout_s=60), (
            procs.stop(trajectory), trajectory.stdout.read())
        with lock:
            points = [m.points for m in got["trajectory"][:4]]
            names = [list(m.joint_names) for m in got["trajectory"][:4]]
        assert names == [["joint1", "joint2"]] * 4
        assert [list(p[0].positions) for p in points] == GOALS
        assert all(len(p) == 1 and p[0].time_from_start.sec == 4 and len(p[0].velocities) == 0 for p in points)
    finally:
        node.close()
    assert procs.stop(forward) == 0 and procs.stop(trajectory) == 0
