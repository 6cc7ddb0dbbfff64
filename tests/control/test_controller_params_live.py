"""A running controller as a ROS 2 node: `diffctl param list/get/set/describe/dump/load` on
/diffbot_base_controller of a manager on mock hardware (real processes, a real router), a limit changed at
runtime shaping the very next commands, read-only parameters refused, and the controller's warnings on /rosout."""

from __future__ import annotations

import threading
import time

import pytest
import yaml
from test_mock_control import CONFIG, CTRL, Recorder, publish_for, spawn, start_manager

from diffctl.client.rosout import ROSOUT_QOS


def param(procs, verb: str, *args: str, opts: tuple[str, ...] = ()) -> tuple[int, str]:
    # `--` so a negative VALUE is not read as an option
    p = procs.diffctl("param", verb, "--timeout", "20", *opts, "--", *args)
    out, _ = p.communicate(timeout=60)
    return p.returncode, out


@pytest.mark.slow
def test_controller_parameters_over_the_cli_and_runtime_limits(router, procs, tmp_path, output_dir, monkeypatch):
    from tests.probe import Probe

    monkeypatch.setenv("ROS_HOME", str(tmp_path))
    log_path = output_dir / "manager.log"
    start_manager(procs, log_path)
    rc, out = spawn(procs, "diffbot_base_controller", "--param-file", str(CONFIG))
    assert rc == 0, out

    node = Probe("test_params_live")
    rosout: list[tuple[str, str]] = []
    lock = threading.Lock()

    def on_log(msg) -> None:
        with lock:
            rosout.append((msg.name, msg.msg))

    node.create_subscription("/rosout", "rcl_interfaces/msg/Log", on_log, qos=ROSOUT_QOS)

    # list / get / describe: the Jazzy declarations, the tutorial file's values.
    rc, out = param(procs, "list", CTRL)
    assert rc == 0, out
    listed = {line.strip() for line in out.splitlines()}
    assert {"wheel_radius", "linear.x.max_velocity", "angular.z.has_acceleration_limits", "cmd_vel_timeout"} <= listed
    rc, out = param(procs, "get", CTRL, "wheel_separation")
    assert (rc, out.strip()) == (0, "Double value is: 0.3")
    rc, out = param(procs, "describe", CTRL, "wheel_radius")
    # diff_drive_controller's YAML: not read-only, `gt<>: [0.0]` → a range starting just above zero.
    assert rc == 0 and "Read only" not in out and "Min value: 5e-324" in out, out

    # set: a value out of the declared range, or breaking a rule, is refused with the reason; nothing changed.
    rc, out = param(procs, "set", CTRL, "wheel_radius", "-0.1")
    assert rc != 0 and "comply with floating point range" in out, out
    rc, out = param(procs, "set", CTRL, "linear.x.max_acceleration", "-2.0")
    assert rc != 0 and "linear.x.max_acceleration" in out, out
    assert param(procs, "get", CTRL, "wheel_radius")[1].strip() == "Double value is: 0.04"

    # dump writes what load reads.
    dump = tmp_path / "dump.yaml"
    rc, out = param(procs, "dump", CTRL, opts=("--output", str(dump)))
    assert rc == 0, out
    dumped = yaml.safe_load(dump.read_text())[CTRL]["ros__parameters"]
    assert dumped["wheel_separation"] == 0.3 and dumped["left_wheel_names"] == ["base_link_to_left_wheel"]
    assert dumped["linear"]["x"]["max_velocity"] == 1.0

    # Drive at 0.5 m/s, then lower linear.x.max_velocity to 0.2 with `param set`: the next commands obey it.
    rec = Recorder()
    node.create_subscription(f"{CTRL}/odom", "nav_msgs/msg/Odometry", rec.on_odom)
    pub = node.create_publisher(f"{CTRL}/cmd_vel", "geometry_msgs/msg/TwistStamped")
    deadline = time.monotonic() + 10
    while (not rec.odom or pub.subscription_count == 0) and time.monotonic() < deadline:
        time.sleep(0.05)
    publish_for(pub, node, 1.0, 0.5)
    assert rec.last_odom()[2] == pytest.approx(0.5)
    rc, out = param(procs, "set", CTRL, "linear.x.max_velocity", "0.2")
    assert (rc, out.strip()) == (0, "Set parameter successful"), out
    t_set = time.time()
    publish_for(pub, node, 1.0, 0.5)  # 1 m/s² brings it from 0.5 to 0.2 within 0.3 s
    after = [s for s in rec.odom if s[0] > t_set + 0.5]
    assert after and all(s[2] == pytest.approx(0.2) for s in after), after[-5:]

    # load: a file raising the limit again (and the timeout), as `ros2 param load` does.
    (tmp_path / "faster.yaml").write_text(
        f"{CTRL}:\n  ros__parameters:\n    linear.x.max_velocity: 0.4\n    cmd_vel_timeout: 0.25\n"
    )
    rc, out = param(procs, "load", CTRL, str(tmp_path / "faster.yaml"))
    assert rc == 0 and "Set parameter linear.x.max_velocity successful" in out, out
    t_load = time.time()
    publish_for(pub, node, 1.0, 0.5)
    after = [s for s in rec.odom if s[0] > t_load + 0.5]
    assert after and all(s[2] == pytest.approx(0.4) for s in after), after[-5:]
    assert param(procs, "get", CTRL, "cmd_vel_timeout")[1].strip() == "Double value is: 0.25"

    # A stale command makes the controller warn; the warning reaches /rosout under the controller's name.
    publish_for(pub, node, 0.2, 0.1, stamp_offset_s=-2.0)
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline:
        with lock:
            hits = [m for n, m in rosout if n.endswith("diffbot_base_controller") and "Ignoring the received" in m]
        if hits:
            break
        time.sleep(0.1)
    assert hits, rosout[-10:]
    assert "Parameters were updated" in log_path.read_text()
    node.close()
