"""OdometryPublisher (ground truth odometry) and the plugin-name alias table, on the real car in real PyBullet
through the simulator's own loop."""

from __future__ import annotations

import math

import pytest
from sim_helpers import CAR, EMPTY_WORLD
from test_plugins import advance

from diffctl.bus import gz
from diffctl.description.sdf_loader import load_world, parse_model
from diffctl.errors import DescriptionError
from diffctl.sim.plugins.diff_drive import DiffDrive
from diffctl.sim.plugins.odometry_publisher import OdometryPublisher
from diffctl.sim.plugins.system_names import system_kind
from diffctl.sim.runner import Simulation


def car_with(plugin_xml: str) -> str:
    text = CAR.read_text()
    i = text.rindex("</model>")
    return text[:i] + plugin_xml + text[i:]


LEGACY_ODOM = """<plugin filename="ignition-gazebo-odometry-publisher-system"
    name="ignition::gazebo::systems::OdometryPublisher">
  <odom_frame>odom</odom_frame><robot_base_frame>base_footprint</robot_base_frame>
  <odom_publish_frequency>20</odom_publish_frequency><dimensions>2</dimensions>
  <xyz_offset>0.1 0 0</xyz_offset>
</plugin>"""


@pytest.mark.parametrize(
    ("filename", "name", "kind"),
    [
        ("gz-sim-odometry-publisher-system", "gz::sim::systems::OdometryPublisher", "odometry-publisher"),
        ("libgz-sim8-pose-publisher-system.so", "", "pose-publisher"),
        ("ignition-gazebo-linearbatteryplugin-system", "", "linearbatteryplugin"),
        ("libignition-gazebo6-diff-drive-system.so", "ignition::gazebo::systems::DiffDrive", "diff-drive"),
        ("/opt/custom/libmy_odom.so", "ignition::gazebo::systems::OdometryPublisher", "odometry-publisher"),
        ("gz_ros2_control-system", "gz_ros2_control::GazeboSimROS2ControlPlugin", "gz_ros2_control"),
    ],
)
def test_every_spelling_of_a_system_names_the_same_kind(filename: str, name: str, kind: str) -> None:
    assert system_kind(filename, name) == kind


def test_odometry_publisher_reports_ground_truth_in_its_frames_at_its_rate() -> None:
    sim = Simulation(load_world(EMPTY_WORLD), rtf=0.0)
    try:
        sim.spawn(parse_model(car_with(LEGACY_ODOM), name="robot", base_dir=CAR.parent))
        rt = sim.models["robot"]
        odom = next(p for p in rt.plugins if isinstance(p, OdometryPublisher))
        drive = next(p for p in rt.plugins if isinstance(p, DiffDrive))
        assert odom.p.rate_hz == 20 and odom.p.odom_topic == "/model/robot/odometry"
        assert odom.p.tf_topic == "/model/robot/pose" and "odometry-publisher" not in sim.model_ignored(rt.entity.model)
        assert odom.message(0) is None  # the first sample initialises
        advance(sim, 200)
        drive.command(0.3, 0.5)
        advance(sim, 3000)
        msg = odom.last_message
        assert gz.stamp_ns(msg["header"]) == sim.stepper.sim_time_ns  # 3.2 s: a 20 Hz tick
        truth = rt.entity.pose()
        yaw = 2 * math.atan2(truth.quat[2], truth.quat[3])
        pos = msg["pose"]["position"]
        # pose = model pose × xyz_offset, flattened to the ground plane
        assert pos["x"] == pytest.approx(truth.xyz[0] + 0.1 * math.cos(yaw), abs=1e-6)
        assert pos["y"] == pytest.approx(truth.xyz[1] + 0.1 * math.sin(yaw), abs=1e-6)
        assert pos["z"] == 0.0
        assert 2 * math.atan2(msg["pose"]["orientation"]["z"], msg["pose"]["orientation"]["w"]) == pytest.approx(
            yaw, abs=1e-6
        )
        tw = msg["twist"]
        # the offset point on a body turning at 0.5 rad/s moves at 0.3 m/s forward plus 0.05 m/s sideways
        assert tw["linear"]["x"] == pytest.approx(0.3, abs=0.02)
        assert tw["linear"]["y"] == pytest.approx(0.05, abs=0.02)
        assert tw["angular"]["z"] == pytest.approx(0.5, abs=0.03)
        assert tw["linear"]["z"] == tw["angular"]["x"] == tw["angular"]["y"] == 0.0
        assert gz.header_value(msg["header"], "frame_id") == "odom"
        assert gz.header_value(msg["header"], "child_frame_id") == "base_footprint"
        # gz-sim 8's odometry_with_covariance: the same sample, the noise's variance on both diagonals
        assert odom.p.odom_covariance_topic == "/model/robot/odometry_with_covariance"
        cov = odom.with_covariance(msg)
        assert cov["header"] is msg["header"] and cov["pose_with_covariance"]["pose"] == msg["pose"]
        assert cov["twist_with_covariance"]["twist"] == msg["twist"]
        assert cov["pose_with_covariance"]["covariance"]["data"] == [0.0] * 36
    finally:
        sim.close()


def test_odometry_with_covariance_carries_the_noise_variance_on_its_topic() -> None:
    sim = Simulation(load_world(EMPTY_WORLD), rtf=0.0)
    try:
        noisy = LEGACY_ODOM.replace(
            "<dimensions>2</dimensions>",
            "<dimensions>3</dimensions><gaussian_noise>0.1</gaussian_noise>"
            "<odom_covariance_topic>/odom_cov</odom_covariance_topic>",
        )
        sim.spawn(parse_model(car_with(noisy), name="robot", base_dir=CAR.parent))
        odom = next(p for p in sim.models["robot"].plugins if isinstance(p, OdometryPublisher))
        assert odom.p.odom_covariance_topic == "/odom_cov" and "/odom_cov" in odom.topics
        advance(sim, 300)
        cov = odom.with_covariance(odom.last_message)
        for part in ("pose_with_covariance", "twist_with_covariance"):
            data = cov[part]["covariance"]["data"]
            assert [data[i * 7] for i in range(6)] == pytest.approx([0.01] * 6)
            assert sum(abs(v) for i, v in enumerate(data) if i % 7) == 0.0
    finally:
        sim.close()


def test_odometry_publisher_refuses_bad_dimensions_naming_the_field() -> None:
    sim = Simulation(load_world(EMPTY_WORLD), rtf=0.0)
    try:
        bad = LEGACY_ODOM.replace("<dimensions>2</dimensions>", "<dimensions>4</dimensions>")
        with pytest.raises(DescriptionError, match=r"dimensions.*not 2 or 3"):
            sim.spawn(parse_model(car_with(bad), name="robot", base_dir=CAR.parent))
    finally:
        sim.close()
