"""GazeboSimSystem against the real simulator: the manager waits for the endpoint, attaches, runs in lockstep on
sim time, drives the wheels; when it leaves, the simulator runs on."""

from __future__ import annotations

import itertools
import json
import subprocess
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SDF = REPO / "description" / "my_diff_car_control.sdf"
CONFIG = REPO / "config" / "diff_drive_controller.yaml"
WORLD = REPO / "config" / "worlds" / "empty.world"


def run(procs, *args: str, timeout_s: float = 30.0) -> tuple[int, str]:
    p = procs.diffctl(*args)
    out, _ = p.communicate(timeout=timeout_s)
    return p.returncode, out


def endpoint_info(session) -> dict:
    from diffctl.bus import hw_endpoint as hw

    for r in session.get(hw.info_key("robot"), payload=b"{}", timeout=2.0):
        if r.ok is not None:
            return json.loads(r.ok.payload.to_bytes())
    raise AssertionError("no answer from the endpoint")


@pytest.mark.slow
def test_manager_attaches_to_the_simulator_and_drives_in_lockstep(router, procs, tmp_path, monkeypatch) -> None:
    from diffctl.bus import Node

    monkeypatch.setenv("ROS_HOME", str(tmp_path))
    sdf = tmp_path / "robot.sdf"
    sdf.write_text(SDF.read_text().replace("PARAMETERS_CONFIG_FILE_PLACEHOLDER", str(CONFIG)))
    cm_log = tmp_path / "manager.log"
    # The manager first: it must wait for the simulator's endpoint, saying so.
    cm = procs.diffctl(
        "control", "manager", "--description", str(sdf), stdout=cm_log.open("w"), stderr=subprocess.STDOUT
    )
    deadline = time.monotonic() + 20
    while "waiting for the simulator's ros2_control endpoint" not in cm_log.read_text():
        assert cm.poll() is None and time.monotonic() < deadline, cm_log.read_text()
        time.sleep(0.1)
    sim_log = tmp_path / "sim.log"
    procs.diffctl(
        "sim", "run", "-r", "-s", "--rtf", "1", str(WORLD), stdout=sim_log.open("w"), stderr=subprocess.STDOUT
    )
    rc, out = run(procs, "spawn", "entity", "--file", str(sdf), "--name", "robot")
    assert rc == 0, out
    rc, out = run(procs, "spawn", "controller", "diffbot_base_controller", "-p", str(CONFIG))
    assert rc == 0, out + cm_log.read_text()
    rc, out = run(procs, "spawn", "controller", "joint_state_broadcaster")
    assert rc == 0, out
    text = cm_log.read_text()
    assert "attached to model 'robot': lockstep every 50 ms of sim time" in text
    assert "20 Hz, sim time" in text

    node = Node("test_sim_teleop")
    joints: list[tuple[float, float]] = []  # (stamp s, left wheel velocity rad/s)
    odom: list[tuple[float, float]] = []

    def on_joints(msg) -> None:
        names = list(msg.name)
        if "base_link_to_left_wheel" in names:
            joints.append(
                (
                    msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9,
                    float(msg.velocity[names.index("base_link_to_left_wheel")]),
                )
            )

    node.create_subscription("/joint_states", "sensor_msgs/msg/JointState", on_joints)
    node.create_subscription(
        "/diffbot_base_controller/odom",
        "nav_msgs/msg/Odometry",
        lambda m: odom.append((m.header.stamp.sec + m.header.stamp.nanosec * 1e-9, m.pose.pose.position.x)),
    )
    pub = node.create_publisher("/diffbot_base_controller/cmd_vel", "geometry_msgs/msg/TwistStamped")
    while (not joints or pub.subscription_count == 0) and time.monotonic() < deadline + 20:
        time.sleep(0.05)
    assert joints, "no /joint_states from the simulated wheels"
    # Stamp 0 = "now" on the controller's (sim) clock.
    end = time.monotonic() + 2.0
    while time.monotonic() < end:
        pub.publish({"twist": {"linear": {"x": 0.2}}})
        time.sleep(0.05)
    # JointStateBroadcaster stamps are sim time, one per 50 ms control period (lockstep: no gaps, no repeats).
    stamps = [t for t, _ in joints]
    steps = {round((b - a) * 1000) for a, b in itertools.pairwise(stamps)}
    assert steps == {50}, steps
    # The simulated wheel follows the command: 0.2 m/s / 0.04 m = 5 rad/s.
    assert joints[-1][1] == pytest.approx(5.0, rel=0.05)
    assert odom[-1][1] > 0.2
    info = endpoint_info(node.session)
    assert info["manager"] and info["lockstep_overruns"] == 0
    node.close()

    # The manager leaves: the simulator detaches and runs on (its clock keeps going).
    assert procs.stop(cm) == 0
    t_before = endpoint_info(Node("test_sim_probe").session)["sim_time_ns"]
    time.sleep(0.5)
    after = endpoint_info(Node("test_sim_probe2").session)
    assert after["manager"] is None and after["sim_time_ns"] > t_before
