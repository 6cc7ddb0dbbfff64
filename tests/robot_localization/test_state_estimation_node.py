"""ekf_node and ukf_node as real processes on a real router, driven on sim time through robot_localization's
own interface test (test/test_se_node_interfaces.cpp and its YAML): the same inputs, rates and durations,
checked against the bounds upstream's test asserts."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml

from tests.robot_localization.harness import SEC, Driver, quat_rpy, rpy_of

ODOM = "nav_msgs/msg/Odometry"
F, T = False, True

# test_se_node_interfaces.yaml, as upstream's test runs both nodes with it (and sim time, here).
UPSTREAM_PARAMS = {
    "frequency": 30.0, "sensor_timeout": 1000.0,
    "odom0": "/odom_input0", "odom1": "/odom_input1", "odom2": "/odom_input2",
    "pose0": "/pose_input0", "pose1": "/pose_input1", "twist0": "/twist_input0",
    "imu0": "/imu_input0", "imu1": "/imu_input1", "imu2": "/imu_input2", "imu3": "/imu_input3",
    "odom0_config": [T, F, T, F, F, F, F, F, F, F, F, F, F, F, F], "odom0_relative": False,
    "odom1_config": [T, T, T, T, T, T, F, F, F, F, F, F, F, F, F], "odom1_relative": False,
    "odom2_config": [F, F, F, F, F, F, T, T, T, T, T, T, F, F, F], "odom2_relative": False,
    "pose0_config": [T, F, T, F, F, F, F, F, F, F, F, F, F, F, F],
    "pose1_config": [T, T, T, T, T, T, F, F, F, F, F, F, F, F, F],
    "twist0_config": [F, F, F, F, F, F, T, T, T, T, T, T, F, F, F],
    "imu0_config": [F, F, F, T, T, T, F, F, F, F, F, F, F, F, F],
    "imu1_config": [F, F, F, F, F, F, F, F, F, T, T, T, F, F, F],
    "imu2_config": [F, F, F, F, F, F, F, F, F, F, F, F, T, T, T],
    "imu3_config": [F, F, F, T, T, T, F, F, F, F, F, F, F, F, F],
    "odom1_differential": True, "pose1_differential": True, "imu3_differential": True,
    "print_diagnostics": False, "odom_frame": "odom", "base_link_frame": "base_link",
    "process_noise_covariance": [1e-6, 1e-6, 1e-6, 1e-6, 1e-6, 1e-6, 0.025, 0.025, 0.05, 0.002, 0.002, 0.004,
                                 0.01, 0.01, 0.01],
    "alpha": 0.001, "kappa": 0.0, "beta": 2.0,
}


def _diag(value: float, size: int = 36, step: int = 7) -> list[float]:
    return [value if i % step == 0 else 0.0 for i in range(size)]


@pytest.fixture(params=["ekf_node", "ukf_node"])
def driver(request, router: str, procs, tmp_path: Path):
    params = tmp_path / "params.yaml"
    # imu0_config as community files write it: nine entries, as the one item of a block list (`- [...]`);
    # rcl flattens the list and upstream reads past its end as false, so the node runs upstream's test the same
    imu0 = [UPSTREAM_PARAMS["imu0_config"][:9]]
    assert not any(UPSTREAM_PARAMS["imu0_config"][9:])
    values = {**UPSTREAM_PARAMS, "imu0_config": imu0, "use_sim_time": True}
    params.write_text(yaml.safe_dump({"/**": {"ros__parameters": values}}))
    node = procs.diffctl("run", "robot_localization", request.param, "--ros-args", "--params-file", str(params))
    d = Driver()
    d.watch("/odometry/filtered", ODOM)
    try:
        yield d
    finally:
        d.close()
        assert procs.stop(node) == 0, node.stdout.read()


def reset(d: Driver) -> None:
    d.call("/reset", "std_srvs/srv/Empty")
    d.forget("/odometry/filtered")


def test_odometry_pose_twist_and_differential(driver: Driver) -> None:
    d = driver
    # OdomPoseBasicIO: x and z fused, y not
    odom = {"header": {"frame_id": "odom"}, "child_frame_id": "base_link",
            "pose": {"pose": {"position": {"x": 20.0, "y": 10.0, "z": -40.0}},
                     "covariance": [2.0 if i in (0, 7, 14) else 0.0 for i in range(36)]}}
    out = d.drive("/odom_input0", ODOM, lambda i: odom, 50, 1 / 50)
    p = out.pose.pose.position
    assert abs(p.x - 20.0) < 0.01 and abs(p.y) < 0.01 and abs(p.z + 40.0) < 0.01, p
    c = out.pose.covariance
    assert c[0] < 0.5 and c[7] < 0.25 and c[14] < 0.6, (c[0], c[7], c[14])
    reset(d)

    # OdomTwistBasicIO: 5 m/s for 20 s, then a quarter turn in 5 s at 1 m/s (x and y equal at its end)
    twist = {"header": {"frame_id": "odom"}, "child_frame_id": "base_link",
             "twist": {"twist": {"linear": {"x": 5.0}}, "covariance": _diag(1e-6)}}
    out = d.drive("/odom_input2", ODOM, lambda i: twist, 400, 1 / 20)
    assert abs(out.twist.twist.linear.x - 5.0) < 0.1
    assert abs(out.pose.pose.position.x - 100.0) < 2.0, out.pose.pose.position
    reset(d)
    turn = (math.pi / 2) / (100.0 * 0.05)
    arc = {**twist, "twist": {"twist": {"linear": {"x": 1.0}, "angular": {"z": turn}}, "covariance": _diag(1e-6)}}
    out = d.drive("/odom_input2", ODOM, lambda i: arc, 100, 1 / 20)
    assert abs(out.twist.twist.linear.x - 1.0) < 0.1 and abs(out.twist.twist.angular.z - turn) < 0.1
    p = out.pose.pose.position
    assert abs(p.x - p.y) < 0.5, p
    reset(d)

    # OdomDifferentialIO: an unchanging pose moves nothing; then +0.01/+0.02/-0.03 per message, 100 times
    diff = {"header": {"frame_id": "odom"}, "child_frame_id": "base_link",
            "pose": {"pose": {"position": {"x": 20.0, "y": 10.0, "z": -40.0}, "orientation": {"w": 1.0}},
                     "covariance": [2.0 if i in (0, 7, 14) else 0.2 if i in (21, 28, 35) else 0.0
                                    for i in range(36)]}}
    d.drive("/odom_input1", ODOM, lambda i: diff, 1, 1 / 10, every=0)  # the first pose only sets the reference
    out = d.drive("/odom_input1", ODOM, lambda i: diff, 9, 1 / 10, every=1)
    p, q = out.pose.pose.position, out.pose.pose.orientation
    assert max(abs(p.x), abs(p.y), abs(p.z), abs(q.x), abs(q.y), abs(q.z), abs(q.w - 1)) < 0.01, out.pose.pose

    def moving(i: int) -> dict:
        k = i + 1
        pose = {"position": {"x": 20.0 + 0.01 * k, "y": 10.0 + 0.02 * k, "z": -40.0 - 0.03 * k},
                "orientation": {"w": 1.0}}
        return {**diff, "pose": {"pose": pose, "covariance": _diag(1e-6)}}

    out = d.drive("/odom_input1", ODOM, moving, 100, 1 / 20)
    p = out.pose.pose.position
    assert abs(p.x - 1) < 0.2 and abs(p.y - 2) < 0.4 and abs(p.z + 3) < 0.6, p


def test_imu_orientation_rates_and_acceleration(driver: Driver) -> None:
    d = driver
    imu_type = "sensor_msgs/msg/Imu"
    # ImuPoseBasicIO: orientation fused as given
    imu = {"header": {"frame_id": "base_link"}, "orientation": quat_rpy(math.pi / 4, -math.pi / 4, math.pi / 2),
           "orientation_covariance": _diag(1e-6, 9, 4)}
    out = d.drive("/imu_input0", imu_type, lambda i: imu, 50, 1 / 50)
    r, p, y = rpy_of(out.pose.pose.orientation)
    assert abs(r - math.pi / 4) < 0.1 and abs(p + math.pi / 4) < 0.1 and abs(y - math.pi / 2) < 0.1, (r, p, y)
    c = out.pose.covariance
    assert c[21] < 0.5 and c[28] < 0.25 and c[35] < 0.5
    reset(d)
    # an orientation covariance of -1 means "no orientation": nothing is fused, nothing published
    ignored = {"header": {"frame_id": "base_link"}, "orientation": {"x": 0.1, "y": 0.2, "z": 0.3, "w": 0.4},
               "orientation_covariance": [-1.0] + [0.0] * 8}
    before = d.count.get("/odometry/filtered", 0)
    pub = d.publisher("/imu_input0", imu_type)
    for _ in range(50):
        d.now_ns += SEC // 50
        d.tick()
        pub.publish(d.stamped(ignored))
    d.call("/toggle", "robot_localization/srv/ToggleFilterProcessing", {"on": True})  # a round trip: all taken
    assert d.count.get("/odometry/filtered", 0) == before
    reset(d)

    # ImuTwistBasicIO: a roll rate of π/2 for 1 s
    rate = {"header": {"frame_id": "base_link"}, "angular_velocity": {"x": math.pi / 2},
            "angular_velocity_covariance": _diag(1e-6, 9, 4)}
    out = d.drive("/imu_input1", imu_type, lambda i: rate, 50, 1 / 50)
    r, p, y = rpy_of(out.pose.pose.orientation)
    assert abs(r - math.pi / 2) < 0.7 and abs(p) < 0.1 and abs(y) < 0.1, (r, p, y)
    assert out.twist.covariance[21] < 1e-3 and out.pose.covariance[21] < 0.1
    reset(d)

    # ImuAccBasicIO: (1, -1, 1) m/s² for 1 s, then none for 1 s
    acc = {"header": {"frame_id": "base_link"}, "linear_acceleration": {"x": 1.0, "y": -1.0, "z": 1.0},
           "linear_acceleration_covariance": _diag(1e-6, 9, 4)}
    out = d.drive("/imu_input2", imu_type, lambda i: acc, 50, 1 / 50)
    v = out.twist.twist.linear
    assert abs(v.x - 1) < 0.4 and abs(v.y + 1) < 0.4 and abs(v.z - 1) < 0.4, v
    still = {**acc, "linear_acceleration": {"x": 0.0, "y": 0.0, "z": 0.0}}
    out = d.drive("/imu_input2", imu_type, lambda i: still, 50, 1 / 50)
    p = out.pose.pose.position
    assert abs(p.x - 1.8) < 0.6 and abs(p.y + 1.8) < 0.6 and abs(p.z - 1.8) < 0.6, p
