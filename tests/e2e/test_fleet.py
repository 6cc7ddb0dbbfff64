"""Three cars in one world (`diffctl launch fleet robots:=3`), each in its own namespace, watched over the bus.

The oracle for where the cars are is the simulator's ground truth (gz /model/robotK/pose), never the
positions the launch file asks for: the lidar check compares robot1's ranges with the distance the ground
truth gives, and the driving check compares every car's ground truth before and after robot2 is driven.
"""

from __future__ import annotations

import math
import subprocess
import sys
import threading
from pathlib import Path
from typing import Any

import pytest

from diffctl.bus import gz
from diffctl.interfaces import types
from tests.e2e.stack import Stack
from tests.waiting import wait_for

pytestmark = pytest.mark.slow
SEC = 1_000_000_000
ROBOTS = ("robot1", "robot2", "robot3")
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"
# Geometry of the tutorial car (description/my_diff_car_control.sdf): robot1's lidar sits 0.05 m behind the
# model origin, and what it sees of a car ahead is that car's lidar puck (radius 0.03 m, 0.05 m behind its
# origin); the other car's chassis is lower than the scan plane.
PUCK_RADIUS_M = 0.03
RANGE_TOLERANCE_M = 0.05


class FleetWatch:
    """Ground truth per car, robot1's latest scan, TF pairs and joint_states seen per namespace."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.truth: dict[str, tuple[float, float]] = {}
        self.scan: Any = None
        self.tf_pairs: set[tuple[str, str]] = set()
        self.joint_states: set[str] = set()

    def on_truth(self, robot: str, sample: Any) -> None:
        _, msg = gz.decode(sample.payload.to_bytes())
        poses = msg.get("pose") or []
        if poses:
            p = poses[0].get("position", {})
            with self.lock:
                self.truth[robot] = (p.get("x", 0.0), p.get("y", 0.0))

    def on_tf(self, msg: Any) -> None:
        with self.lock:
            self.tf_pairs.update((t.header.frame_id, t.child_frame_id) for t in msg.transforms)

    def position(self, robot: str) -> tuple[float, float]:
        with self.lock:
            return self.truth[robot]


def range_towards(scan: Any, angle_rad: float, half_width_rad: float = math.radians(4)) -> float:
    """The shortest range of `scan` within `half_width_rad` of `angle_rad`."""
    best = math.inf
    for i, r in enumerate(scan.ranges):
        a = scan.angle_min + i * scan.angle_increment
        if abs(math.remainder(a - angle_rad, math.tau)) <= half_width_rad and math.isfinite(r):
            best = min(best, r)
    return best


def expected_range(watch: FleetWatch, other: str, axis: int) -> float:
    """robot1's lidar to `other`'s puck along x (axis 0) or y (axis 1), from the ground truth."""
    return watch.position(other)[axis] - watch.position("robot1")[axis] - PUCK_RADIUS_M


def test_three_cars_namespaced_driven_and_seeing_each_other(tmp_path: Path, stack_env: str) -> None:
    stack = Stack("fleet", tmp_path, "robots:=3", rtf="2")
    try:
        node = stack.connect()
        watch = FleetWatch()
        subs = [
            node.session.declare_subscriber(gz.key(f"/model/{r}/pose"), lambda s, r=r: watch.on_truth(r, s))
            for r in ROBOTS
        ]
        node.create_subscription("/tf", "tf2_msgs/msg/TFMessage", watch.on_tf)
        node.create_subscription("/tf_static", "tf2_msgs/msg/TFMessage", watch.on_tf, latched=True)
        for r in ROBOTS:
            node.create_subscription(f"/{r}/joint_states", "sensor_msgs/msg/JointState",
                                     lambda m, r=r: watch.joint_states.add(r))

        def on_scan(m: Any) -> None:
            watch.scan = m

        node.create_subscription("/robot1/scan", "sensor_msgs/msg/LaserScan", on_scan)

        # Every car's own controller manager, asked over the bus; robot2's also through the CLI, relative -c.
        for r in ROBOTS:
            client = node.create_client(f"/{r}/controller_manager/list_controllers",
                                        "controller_manager_msgs/srv/ListControllers")

            def active(client: Any = client) -> bool:
                try:
                    states = {c.name: c.state for c in client.call({}, timeout=2.0).controller}
                except Exception:
                    return False
                return states == {"diffbot_base_controller": "active", "joint_state_broadcaster": "active"}

            assert wait_for(active, 120.0), f"{r}'s controllers never became active:\n{stack.output()}"
        cli = subprocess.run(
            [sys.executable, "-m", "diffctl", "control", "list_controllers", "-c", "robot2/controller_manager"],
            capture_output=True, text=True, timeout=60,
        )
        assert cli.returncode == 0, cli.stderr
        assert "diffbot_base_controller" in cli.stdout and "active" in cli.stdout

        assert wait_for(lambda: set(watch.truth) == set(ROBOTS) and watch.scan is not None, 60.0), stack.output()
        assert wait_for(lambda: watch.joint_states == set(ROBOTS), 30.0), watch.joint_states
        for r in ROBOTS:
            assert (f"{r}/odom", f"{r}/base_footprint") in watch.tf_pairs  # diff_drive: namespace as tf prefix
            assert (f"{r}/base_link", f"{r}/left_wheel") in watch.tf_pairs  # robot_state_publisher frame_prefix
            assert (f"{r}/base_link", f"{r}/lidar_link") in watch.tf_pairs
        assert all(not child.startswith("/") and "/" in child for _, child in watch.tf_pairs), watch.tf_pairs

        assert watch.scan.header.frame_id == "robot1/lidar_link"  # its TF frame, prefixed as robot_state_publisher's
        # robot2 stands in front of robot1 (+x) and robot3 to its left (+y): robot1's lidar sees both.
        stack.wait_sim(stack.clock_ns + SEC)
        ahead, left = expected_range(watch, "robot2", 0), expected_range(watch, "robot3", 1)
        assert abs(range_towards(watch.scan, 0.0) - ahead) < RANGE_TOLERANCE_M, (watch.scan.ranges, ahead)
        assert abs(range_towards(watch.scan, math.pi / 2) - left) < RANGE_TOLERANCE_M, (watch.scan.ranges, left)

        # Drive robot2 forward for 2 s of sim time: it moves, nothing else does.
        before = {r: watch.position(r) for r in ROBOTS}
        stack.watch_odom("/robot2/diffbot_base_controller/odom")
        stack.command("/robot2/diffbot_base_controller/cmd_vel", TWIST_STAMPED, {"twist": {"linear": {"x": 0.5}}})
        stack.wait_sim(stack.clock_ns + 2 * SEC)
        stack.command("/robot2/diffbot_base_controller/cmd_vel", TWIST_STAMPED, None)
        stack.wait_sim(stack.clock_ns + 2 * SEC)  # cmd_vel_timeout brakes it; it comes to rest
        after = {r: watch.position(r) for r in ROBOTS}
        assert after["robot2"][0] - before["robot2"][0] > 0.4, (before, after)
        assert abs(after["robot2"][1] - before["robot2"][1]) < 0.05, (before, after)
        for r in ("robot1", "robot3"):
            assert math.dist(after[r], before[r]) < 0.01, (r, before, after)
        # robot2's own odometry followed it; robot1's lidar now finds it farther, where the ground truth is.
        odom = stack.watch.last(stack.watch.odom)
        assert odom is not None and abs(odom.value[0] - (after["robot2"][0] - before["robot2"][0])) < 0.1
        scan_stamp = types.time_ns(watch.scan.header.stamp)
        assert wait_for(lambda: types.time_ns(watch.scan.header.stamp) > scan_stamp, 30.0)
        ahead_after = expected_range(watch, "robot2", 0)
        assert ahead_after > ahead + 0.4
        assert abs(range_towards(watch.scan, 0.0) - ahead_after) < RANGE_TOLERANCE_M, (watch.scan.ranges, ahead_after)
        for s in subs:
            s.undeclare()
        assert stack.stop() == 0, stack.output()
        assert not stack.survivors()
    finally:
        stack.kill()
