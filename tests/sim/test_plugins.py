"""Gazebo systems inside a Simulation without a bus: DiffDrive, JointStatePublisher; gz_ros2_control's parameters."""

from __future__ import annotations

import threading

import pytest
from sim_helpers import CAR, CAR_CONTROL, EMPTY_WORLD, LEFT, REPO, RIGHT, box, sdf_world

from diffctl.description.sdf_loader import load_model, load_world, parse_model
from diffctl.sim.plugins.diff_drive import DiffDrive
from diffctl.sim.plugins.joint_state_publisher import JointStatePublisher
from diffctl.sim.runner import Simulation

CONTROLLERS = REPO / "config" / "diff_drive_controller.yaml"


def advance(sim: Simulation, steps: int) -> None:
    """Run exactly `steps` physics steps through the real loop (tasks, hooks), then return."""
    done = threading.Event()
    sim.stepper.set_paused(True)
    sim.stepper.step_n(steps, done.set)
    sim.run(done)


def car_sim(path=CAR, seed: int = 0) -> Simulation:
    sim = Simulation(load_world(EMPTY_WORLD), rtf=0.0, seed=seed)
    sim.spawn(load_model(path, name="robot"))
    return sim


def test_diff_drive_follows_twists_within_the_sdf_limits_and_drops_nan() -> None:
    sim = car_sim()
    try:
        drive = next(p for p in sim.models["robot"].plugins if isinstance(p, DiffDrive))
        assert drive.p.linear.max_velocity == 1.0 and drive.p.angular.max_velocity == 2.0
        advance(sim, 100)
        drive.command(0.4, 0.0)
        advance(sim, 2000)
        assert drive.odom.linear_m_s == pytest.approx(0.4, rel=0.01)
        assert drive.odom.x_m == pytest.approx(0.8, rel=0.03)  # odometry from wheel angles, as Gazebo's
        drive.command(float("nan"), 0.0)  # dropped: the last good command holds
        drive.command(0.0, float("inf"))
        advance(sim, 200)
        assert drive.odom.linear_m_s == pytest.approx(0.4, rel=0.01)
        drive.command(1e300, -1e300)  # absurd: clamped to the SDF's max_linear / min_angular velocity
        advance(sim, 500)
        assert drive.odom.linear_m_s == pytest.approx(1.0, rel=0.02)
        assert drive.odom.angular_rad_s == pytest.approx(-2.0, rel=0.03)
        car = sim.models["robot"].entity
        states = car.joint_states([car.joint(LEFT), car.joint(RIGHT)])
        assert all(abs(s[1]) <= 40.0 + 1e-6 for s in states)  # the joints' <velocity> limit
    finally:
        sim.close()


def test_joint_state_publisher_message() -> None:
    sim = car_sim()
    try:
        jsp = next(p for p in sim.models["robot"].plugins if isinstance(p, JointStatePublisher))
        assert jsp.topic == "joint_states"
        msg = jsp.message(5)
        assert msg["name"] == "robot" and [j["name"] for j in msg["joint"]] == [LEFT, RIGHT]
        assert set(msg["joint"][0]["axis1"]) == {"position", "velocity", "force"}
    finally:
        sim.close()


def _run_drive(seed: int) -> list[tuple]:
    sim = car_sim(seed=seed)
    try:
        sim.spawn(sdf_world(box("wall", 2.0, 0, 0.5, 0.2, 8, 1)).model("wall"))
        drive = next(p for p in sim.models["robot"].plugins if isinstance(p, DiffDrive))
        out = []
        for k, (v, w) in enumerate([(0.3, 0.0), (0.5, 1.0), (-0.2, -0.5), (0.0, 2.0)]):
            drive.command(v, w)
            advance(sim, 700 + 13 * k)
            p = sim.models["robot"].entity.pose()
            out.append((*p.xyz, *p.quat, drive.odom.x_m, drive.odom.heading_rad))
        lidar = next(s for s in sim.models["robot"].sensors if type(s).__name__ == "Lidar")
        out.append(tuple(lidar.scan().tolist()))
        return out
    finally:
        sim.close()


def test_same_world_commands_and_seed_give_bit_identical_runs() -> None:
    a, b = _run_drive(3), _run_drive(3)
    assert a == b
    c = _run_drive(4)  # another seed: the same physics, other sensor noise
    assert a[:-1] == c[:-1] and a[-1] != c[-1]


def test_gz_ros2_control_needs_the_bus() -> None:
    from diffctl.errors import ConfigError

    sim = Simulation(load_world(EMPTY_WORLD), rtf=0.0)
    try:
        text = CAR_CONTROL.read_text().replace("PARAMETERS_CONFIG_FILE_PLACEHOLDER", str(CONTROLLERS))
        with pytest.raises(ConfigError, match="needs the bus"):
            sim.spawn(parse_model(text, name="robot"), text)
        assert "robot" not in sim.models  # nothing half-spawned
    finally:
        sim.close()


def test_gz_ros2_control_and_joint_state_publisher_parameters() -> None:
    from diffctl.description.model import Plugin
    from diffctl.errors import DescriptionError
    from diffctl.sim.plugins.gz_ros2_control import GzRos2ControlParams
    from diffctl.sim.plugins.joint_state_publisher import JointStatePublisherParams

    name, filename = "gz_ros2_control::GazeboSimROS2ControlPlugin", "libgz_ros2_control-system"
    p = GzRos2ControlParams.from_plugin(Plugin(name, filename, (("parameters", "/a.yaml"),)), "t")
    assert (p.hold_joints, p.position_proportional_gain, p.parameters) == (True, 0.1, ("/a.yaml",))
    assert (p.namespace, p.remappings, p.controller_manager_name) == ("/", (), "controller_manager")
    off = Plugin(name, filename, (("hold_joints", "false"), ("parameters", "/a.yaml"), ("parameters", "/b.yaml")))
    assert GzRos2ControlParams.from_plugin(off, "t").hold_joints is False
    assert GzRos2ControlParams.from_plugin(off, "t").parameters == ("/a.yaml", "/b.yaml")  # later ones override
    with pytest.raises(DescriptionError, match="'flase' is not a boolean"):
        GzRos2ControlParams.from_plugin(Plugin(name, filename, (("hold_joints", "flase"), ("parameters", "/a"))), "t")
    with pytest.raises(DescriptionError, match="needs a <parameters> file"):
        GzRos2ControlParams.from_plugin(Plugin(name, filename, ()), "t")
    jsp = Plugin("gz::sim::systems::JointStatePublisher", "gz-sim-joint-state-publisher-system", ())
    jp = JointStatePublisherParams.from_plugin(jsp, "empty", "robot")
    assert (jp.topic, jp.update_rate_hz, jp.joint_names) == ("/world/empty/model/robot/joint_state", 50.0, ())
    with pytest.raises(DescriptionError, match="'-5'"):
        JointStatePublisherParams.from_plugin(Plugin(jsp.name, jsp.filename, (("update_rate", "-5"),)), "w", "m")
