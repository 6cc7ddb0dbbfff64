"""PosePublisher on the real car in real PyBullet: which entities, their frames, poses relative to the parent,
static and dynamic groups, and its rates."""

from __future__ import annotations

import math

import pytest
from sim_helpers import CAR, EMPTY_WORLD
from test_odometry_publisher import car_with
from test_plugins import advance

from diffctl.bus import gz
from diffctl.description.sdf_loader import load_world, parse_model
from diffctl.sim.plugins.diff_drive import DiffDrive
from diffctl.sim.plugins.pose_publisher import PosePublisher
from diffctl.sim.runner import Simulation


def pose_sim(params: str) -> tuple[Simulation, PosePublisher]:
    sim = Simulation(load_world(EMPTY_WORLD), rtf=0.0)
    plugin = f'<plugin filename="gz-sim-pose-publisher-system" name="gz::sim::systems::PosePublisher">{params}</plugin>'
    sim.spawn(parse_model(car_with(plugin), name="robot", base_dir=CAR.parent))
    rt = sim.models["robot"]
    return sim, next(p for p in rt.plugins if isinstance(p, PosePublisher))


def by_child(poses: list[dict]) -> dict[str, dict]:
    return {p["name"]: p for p in poses}


def test_defaults_publish_every_link_relative_to_the_model_every_step() -> None:
    sim, pp = pose_sim("")
    try:
        assert pp.topics == ("/model/robot/pose",) and not pp.p.pose_vector and pp.p.rate_hz == -1
        assert pp._tasks[0].period_ns == sim.stepper.step_ns
        advance(sim, 300)
        poses = by_child(pp.poses(sim.stepper.sim_time_ns, static=False))
        assert set(poses) == {
            f"robot::{n}"
            for n in (
                "base_footprint",
                "base_link",
                "left_wheel",
                "right_wheel",
                "caster",
                "lidar_link",
                "imu_link",
                "camera_link",
            )
        }
        wheel = poses["robot::left_wheel"]
        assert gz.header_value(wheel["header"], "frame_id") == "robot"
        assert gz.header_value(wheel["header"], "child_frame_id") == "robot::left_wheel"
        # the wheel sits 0.15 m to the left of base_link, at the axle height 0.04 m, in the model frame
        assert (wheel["position"]["x"], wheel["position"]["y"], wheel["position"]["z"]) == pytest.approx(
            (0.0, 0.15, 0.04), abs=1e-3
        )
    finally:
        sim.close()


def test_static_publisher_splits_moving_links_from_the_rest_and_poses_follow_the_wheels() -> None:
    sim, pp = pose_sim(
        "<publish_sensor_pose>true</publish_sensor_pose><publish_model_pose>true</publish_model_pose>"
        "<static_publisher>true</static_publisher><use_pose_vector_msg>true</use_pose_vector_msg>"
        "<update_frequency>100</update_frequency><static_update_frequency>1</static_update_frequency>"
    )
    try:
        assert pp.topics == ("/model/robot/pose", "/model/robot/pose_static")
        assert [t.period_ns for t in pp._tasks] == [10_000_000, 1_000_000_000]
        dynamic = by_child(pp.poses(0, static=False))
        static = by_child(pp.poses(0, static=True))
        # gz-sim's rule: both links of every non-fixed joint, except the canonical link (base_footprint here)
        assert set(dynamic) == {"robot::base_link", "robot::left_wheel", "robot::right_wheel"}
        assert {"robot", "robot::base_footprint", "robot::lidar_link::lidar", "robot::imu_link::imu"} <= set(static)
        model = static["robot"]
        assert gz.header_value(model["header"], "frame_id") == "empty"  # the world
        imu = static["robot::imu_link::imu"]
        assert gz.header_value(imu["header"], "frame_id") == "robot::imu_link"
        drive = next(p for p in sim.models["robot"].plugins if isinstance(p, DiffDrive))
        drive.command(0.0, 1.0)
        advance(sim, 500)
        wheel = by_child(pp.poses(sim.stepper.sim_time_ns, static=False))["robot::left_wheel"]
        q = wheel["orientation"]
        pitch = math.asin(max(-1.0, min(1.0, 2 * (q["w"] * q["y"] - q["z"] * q["x"]))))
        assert abs(pitch) > 0.05  # the wheel turned about its axle relative to the model
    finally:
        sim.close()
