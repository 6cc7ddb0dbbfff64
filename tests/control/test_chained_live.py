"""A controller chained in front of diff_drive_controller over real processes: the manager on mock hardware,
the spawners, a forward_command_controller/ForwardCommandController claiming the diff drive's reference
interfaces; commands on its topic drive the car, the diff drive's own cmd_vel is not read meanwhile."""

from __future__ import annotations

import time

import pytest
from test_mock_control import CONFIG, CTRL, Recorder, spawn, start_manager

FWD_YAML = """\
chain_input:
  ros__parameters:
    type: forward_command_controller/ForwardCommandController
    joints: [diffbot_base_controller/linear, diffbot_base_controller/angular]
    interface_name: velocity
"""


@pytest.mark.slow
def test_a_forward_controller_chained_in_front_drives_the_car(router, procs, tmp_path, output_dir, monkeypatch):
    from diffctl.interfaces import types
    from tests.probe import Probe

    monkeypatch.setenv("ROS_HOME", str(tmp_path))
    start_manager(procs, output_dir / "manager.log")
    rc, out = spawn(procs, "diffbot_base_controller", "--param-file", str(CONFIG))
    assert rc == 0, out
    (tmp_path / "chain.yaml").write_text(FWD_YAML)
    rc, out = spawn(procs, "chain_input", "--param-file", str(tmp_path / "chain.yaml"))
    assert rc == 0, out

    node = Probe("test_chain")
    rec = Recorder()
    node.create_subscription(f"{CTRL}/odom", "nav_msgs/msg/Odometry", rec.on_odom)
    fwd = node.create_publisher("/chain_input/commands", "std_msgs/msg/Float64MultiArray")
    cmd_vel = node.create_publisher(f"{CTRL}/cmd_vel", "geometry_msgs/msg/TwistStamped")
    deadline = time.monotonic() + 10
    while (not rec.odom or fwd.subscription_count == 0) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert fwd.subscription_count, "chain_input has no ~/commands subscription"

    # The diff drive is in chained mode: its cmd_vel is not read.
    for _ in range(30):
        cmd_vel.publish(types.new("geometry_msgs/msg/TwistStamped", {"twist": {"linear": {"x": 0.5}}}))
        time.sleep(0.02)
    assert not rec.odom or rec.last_odom()[2] == 0.0

    # The chained controller's command goes through the diff drive's limiter (1 m/s²) to the wheels.
    t0 = time.time()
    for _ in range(75):
        fwd.publish(types.new("std_msgs/msg/Float64MultiArray", {"data": [0.3, 0.0]}))
        time.sleep(0.02)
    moving = [s for s in rec.odom if s[0] > t0 + 0.6]
    assert moving and all(s[2] == pytest.approx(0.3) for s in moving), rec.odom[-5:]
    node.close()
