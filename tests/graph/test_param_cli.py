"""`diffctl param` against real processes: the controller manager on mock hardware, a controller, and
robot_state_publisher — read, set, dump and load as `ros2 param` would, a limit changed at runtime, and a
controller's warning on /rosout."""

from __future__ import annotations

import subprocess
import time
from pathlib import Path

import pytest
import yaml

from tests.control.test_mock_control import CONFIG, SDF, Recorder, publish_for, spawn, start_manager

pytestmark = pytest.mark.slow
CTRL = "/diffbot_base_controller"


def param(procs, *args: str, timeout_s: float = 30.0) -> tuple[int, str]:
    p = procs.diffctl("param", *args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    out, _ = p.communicate(timeout=timeout_s)
    return p.returncode, out


def wait_for(pred, timeout_s: float = 20.0) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if pred():
            return True
        time.sleep(0.05)
    return bool(pred())


def test_param_on_manager_controller_and_robot_state_publisher(router, procs, tmp_path: Path, output_dir,
                                                               monkeypatch) -> None:
    from tests.probe import Probe

    monkeypatch.setenv("ROS_HOME", str(tmp_path))
    start_manager(procs, output_dir / "manager.log")
    rc, out = spawn(procs, "diffbot_base_controller", "--param-file", str(CONFIG))
    assert rc == 0, out
    rsp_params = tmp_path / "rsp.yaml"
    rsp_params.write_text(yaml.safe_dump({"robot_state_publisher": {"ros__parameters": {
        "robot_description": SDF.read_text(), "use_sim_time": False}}}))
    procs.diffctl("robot-state-publisher", "--ros-args", "--params-file", str(rsp_params),
                  stdout=(output_dir / "rsp.log").open("w"), stderr=subprocess.STDOUT)

    node = Probe("param_test")
    logs: list = []
    node.create_subscription("/rosout", "rcl_interfaces/msg/Log", logs.append, latched=True, depth=1000)
    rec = Recorder()
    node.create_subscription(f"{CTRL}/odom", "nav_msgs/msg/Odometry", rec.on_odom)
    pub = node.create_publisher(f"{CTRL}/cmd_vel", "geometry_msgs/msg/TwistStamped")
    assert wait_for(lambda: rec.odom and pub.subscription_count > 0), "the controller never published odometry"

    # The controller: its parameters, typed as its YAML gave them.
    rc, out = param(procs, "list", CTRL)
    assert rc == 0, out
    assert {"wheel_separation", "linear.x.max_velocity", "cmd_vel_timeout", "use_sim_time"} <= set(out.split())
    rc, out = param(procs, "get", CTRL, "wheel_separation")
    assert (rc, out.strip()) == (0, "Double value is: 0.3")

    # A limit changed at runtime takes effect on the next command.
    rc, out = param(procs, "set", CTRL, "linear.x.max_velocity", "0.1")
    assert (rc, out.strip()) == (0, "Set parameter successful"), out
    publish_for(pub, node, 1.5, 0.5)
    top = max(vx for _, _, vx in rec.odom[-20:])
    assert top == pytest.approx(0.1, abs=1e-6), f"the new max_velocity was not applied (top speed {top})"

    # dump writes the YAML load reads back.
    dump = tmp_path / "ctrl.yaml"
    rc, out = param(procs, "dump", CTRL, "--output", str(dump))
    assert rc == 0, out
    data = yaml.safe_load(dump.read_text())
    assert data[CTRL]["ros__parameters"]["linear"]["x"]["max_velocity"] == 0.1
    data[CTRL]["ros__parameters"]["linear"]["x"]["max_velocity"] = 0.25
    dump.write_text(yaml.safe_dump(data))
    rc, out = param(procs, "load", CTRL, str(dump))
    assert rc == 0, out
    assert "Set parameter linear.x.max_velocity successful" in out
    rc, out = param(procs, "get", CTRL, "linear.x.max_velocity", "--hide-type")
    assert (rc, out.strip()) == (0, "0.25")

    # A stale command: the controller warns, and the warning is on /rosout with where it came from.
    publish_for(pub, node, 0.3, 0.2, stamp_offset_s=-2.0)
    assert wait_for(lambda: any(m.name.endswith("diffbot_base_controller") and m.level == 30 for m in logs)), \
        [(m.name, m.msg) for m in logs][-10:]
    warn = next(m for m in logs if m.name.endswith("diffbot_base_controller") and m.level == 30)
    assert warn.file.endswith(".py") and warn.function and warn.line > 0

    # The manager.
    rc, out = param(procs, "get", "/controller_manager", "update_rate")
    assert (rc, out.strip()) == (0, "Integer value is: 20"), out
    rc, out = param(procs, "list", "/controller_manager")
    assert rc == 0 and "update_rate" in out.split(), out

    # robot_state_publisher.
    rc, out = param(procs, "dump", "/robot_state_publisher")
    assert rc == 0, out
    rsp = yaml.safe_load(out)["/robot_state_publisher"]["ros__parameters"]
    assert rsp["robot_description"].strip() == SDF.read_text().strip() and rsp["use_sim_time"] is False
    rc, out = param(procs, "set", "/robot_state_publisher", "use_sim_time", "7")
    assert rc != 0 and "is of type {bool}" in out, out
    rc, out = param(procs, "describe", "/robot_state_publisher", "use_sim_time")
    assert rc == 0 and "Type: boolean" in out, out
    node.close()
