"""A user's own workspace, run unmodified from its root: the tutorial's launch file (controller manager inside
the simulator), its rgbd camera and bridge config, and the mock-hardware variant with no simulator."""

from __future__ import annotations

import signal
import time
from pathlib import Path
from typing import Any

import pytest

from tests.e2e.stack import Stack
from tests.e2e.user_workspace import build

SEC = 1_000_000_000
CONTROLLERS = ("diffbot_base_controller", "joint_state_broadcaster")
CMD = "/diffbot_base_controller/cmd_vel"


def _wait(pred: Any, timeout_s: float, what: str, stack: Stack) -> None:
    deadline = time.monotonic() + timeout_s
    while not pred():
        assert time.monotonic() < deadline, f"timed out waiting for {what}\n{stack.output()}"
        assert stack.proc.poll() is None, f"the launch ended:\n{stack.output()}"
        time.sleep(0.05)


@pytest.mark.slow
def test_the_tutorial_workspace_runs_from_its_root(stack_env: str, tmp_path: Path) -> None:
    ws = build(tmp_path)
    stack = Stack(["diff_sim", "sim_control_gz.launch.py"], tmp_path, rtf=None, cwd=ws)
    try:
        node = stack.connect()
        stack.watch_odom("/diffbot_base_controller/odom")
        seen: dict[str, list[Any]] = {t: [] for t in ("points", "depth", "info")}
        node.create_subscription("/camera/points", "sensor_msgs/msg/PointCloud2", seen["points"].append)
        node.create_subscription("/camera/depth_image", "sensor_msgs/msg/Image", seen["depth"].append)
        node.create_subscription("/camera/camera_info", "sensor_msgs/msg/CameraInfo", seen["info"].append)
        stack.wait_controllers_active(CONTROLLERS)
        # The user's packages were used (diffctl's own demo has no sdf/my_diff_car_control_gz.sdf), and the
        # manager came from the simulator: the launch file starts none.
        assert "ros2_control_node" not in stack.output()
        w = stack.watch
        _wait(lambda: w.last(w.odom) is not None, 60, "odometry", stack)
        stack.command(CMD, "geometry_msgs/msg/TwistStamped", {"twist": {"linear": {"x": 0.3}}})
        start = w.last(w.odom)
        stack.wait_sim(start.t_ns + 3 * SEC, timeout_s=90)
        stack.command(CMD, "geometry_msgs/msg/TwistStamped", None)
        moved = w.last(w.odom).value[0] - start.value[0]
        assert moved > 0.3, f"the car moved only {moved:.3f} m in 3 s at 0.3 m/s"
        truth = w.last(w.truth)
        assert truth is not None and truth.value[0] > 0.3  # the simulated car, not only its odometry
        _wait(lambda: all(seen.values()), 60, "the rgbd camera's points, depth image and camera_info", stack)
        _wait(lambda: w.stamps.get("/scan"), 30, "/scan", stack)
        info, depth, points = seen["info"][-1], seen["depth"][-1], seen["points"][-1]
        assert (info.width, info.height) == (800, 600) and info.k[0] > 0
        assert depth.encoding == "32FC1" and (depth.width, depth.height) == (800, 600)
        assert points.width * points.height > 0 and {f.name for f in points.fields} >= {"x", "y", "z"}
        assert stack.stop(signal.SIGINT) == 0, stack.output()
    finally:
        stack.kill()


@pytest.mark.slow
def test_the_mock_hardware_variant_runs_without_a_simulator(stack_env: str, tmp_path: Path) -> None:
    ws = build(tmp_path)
    stack = Stack(["diff_sim", "mock_control.launch.py"], tmp_path, rtf=None, cwd=ws)
    try:
        stack.connect()
        stack.watch_odom("/diffbot_base_controller/odom")
        stack.wait_controllers_active(CONTROLLERS)
        w = stack.watch
        _wait(lambda: w.last(w.odom) is not None, 30, "odometry", stack)
        stack.command(CMD, "geometry_msgs/msg/TwistStamped", {"twist": {"linear": {"x": 0.3}}})
        start = w.last(w.odom)
        _wait(lambda: w.last(w.odom).t_ns > start.t_ns + 2 * SEC, 30, "two seconds of odometry", stack)
        assert w.last(w.odom).value[0] - start.value[0] > 0.3
        assert stack.stop(signal.SIGINT) == 0, stack.output()
    finally:
        stack.kill()
