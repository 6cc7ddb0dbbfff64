"""The controller spawner's Jazzy flags against a real manager on mock hardware over a real router.

`-c` with and without a leading slash, `--controller-ros-args` reaching the controller's node (a remapped
`~/cmd_vel` that drives, a `-p` value), `-t`, `-n`, `--unload-on-kill` on SIGINT, and `--activate-as-group`.
"""

from __future__ import annotations

import signal
import subprocess
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SDF = REPO / "description" / "my_diff_car_control.sdf"
CONFIG = REPO / "config" / "diff_drive_controller.yaml"


def wait_for(pred, timeout_s: float = 30.0, what: str = "") -> None:
    deadline = time.monotonic() + timeout_s
    while not pred():
        assert time.monotonic() < deadline, f"timed out waiting for {what}"
        time.sleep(0.05)


def finish(p: subprocess.Popen, timeout_s: float = 180.0) -> tuple[int, str]:
    out, _ = p.communicate(timeout=timeout_s)
    return p.returncode, out


@pytest.mark.slow
def test_spawner_flags_on_a_named_manager(router, procs, tmp_path, monkeypatch) -> None:
    from diffctl.client import runtime
    from diffctl.client.node import Node as ClientNode
    from diffctl.client.signals import SignalHandlerOptions
    from diffctl.control.cm_client import ManagerClient
    from tests.probe import Probe

    monkeypatch.setenv("ROS_HOME", str(tmp_path))
    manager_params = tmp_path / "manager.yaml"
    manager_params.write_text("my_ctrl_mgr:\n  ros__parameters:\n    update_rate: 50\n    use_sim_time: false\n")
    log = tmp_path / "manager.log"
    procs.diffctl(
        "control",
        "manager",
        "--param-file",
        str(manager_params),
        "--hardware-plugin",
        "mock_components/GenericSystem",
        "--ros-args",
        "-r",
        "__node:=my_ctrl_mgr",
        stdout=log.open("w"),
        stderr=subprocess.STDOUT,
    )
    node = Probe("test_spawner_flags")
    node.create_publisher("/robot_description", "std_msgs/msg/String", latched=True).publish({"data": SDF.read_text()})
    runtime.init(args=["test_spawner_flags"], signal_handler_options=SignalHandlerOptions.NO)
    try:
        client = ClientNode("test_spawner_flags_client")
        cm = ManagerClient(client, "/my_ctrl_mgr")
        cm.wait("list_controllers", 180.0)
        _flags(procs, tmp_path, node, cm)
        cm.close()
        client.destroy_node()
    finally:
        runtime.try_shutdown()
    node.close()


def _flags(procs, tmp_path, node, cm) -> None:

    # A relative -c, a remap and a parameter for the controller's own node, as a launch file passes them.
    code, out = finish(
        procs.diffctl(
            "spawn",
            "controller",
            "diffbot_base_controller",
            "-c",
            "my_ctrl_mgr",
            "--param-file",
            str(CONFIG),
            "--controller-ros-args",
            "-r ~/cmd_vel:=/cmd_vel",
            "--controller-ros-args",
            "-p cmd_vel_timeout:=2.0",
        )
    )
    assert code == 0, out
    assert cm.controller_state("diffbot_base_controller") == "active"

    odom_x: list[float] = []
    node.create_subscription(
        "/diffbot_base_controller/odom", "nav_msgs/msg/Odometry", lambda m: odom_x.append(m.pose.pose.position.x)
    )
    cmd = node.create_publisher("/cmd_vel", "geometry_msgs/msg/TwistStamped")
    twist = {"header": {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": ""}, "twist": {"linear": {"x": 0.3}}}

    def driven() -> bool:
        cmd.publish(twist)
        return len(odom_x) > 1 and odom_x[-1] > 0.05

    wait_for(driven, 180.0, "odometry to move on /cmd_vel")
    params = node.create_client("/diffbot_base_controller/get_parameters", "rcl_interfaces/srv/GetParameters")
    assert params.wait_for_service(timeout=10.0)
    (value,) = params.call({"names": ["cmd_vel_timeout"]}, timeout=10.0).values
    assert value.double_value == 2.0

    # A leading slash, -t for a controller no file describes, --unload-on-kill ended by SIGINT.
    jsb = procs.diffctl(
        "spawn",
        "controller",
        "jsb",
        "-c",
        "/my_ctrl_mgr",
        "-t",
        "joint_state_broadcaster/JointStateBroadcaster",
        "--unload-on-kill",
    )
    wait_for(lambda: cm.controller_state("jsb") == "active", 180.0, "jsb active")
    jsb.send_signal(signal.SIGINT)
    code, out = finish(jsb)
    assert code == 0, out
    assert cm.controller_state("jsb") is None, out

    # -n: the spawner's namespace, for a relative -c (nothing answers at /robot1/my_ctrl_mgr).
    code, out = finish(
        procs.diffctl(
            "spawn", "controller", "jsb", "-n", "robot1", "-c", "my_ctrl_mgr", "--controller-manager-timeout", "1"
        )
    )
    assert code == 1 and "/robot1/my_ctrl_mgr/list_controllers" in out and "deprecated" in out, out

    # Two controllers in one switch, their types from two parameter files (later files win).
    (tmp_path / "a.yaml").write_text(
        "jsb2:\n  ros__parameters:\n    type: joint_state_broadcaster/JointStateBroadcaster\n"
        "jsb3:\n  ros__parameters:\n    type: no_such/Controller\n"
    )
    (tmp_path / "b.yaml").write_text(
        "jsb3:\n  ros__parameters:\n    type: joint_state_broadcaster/JointStateBroadcaster\n"
    )
    code, out = finish(
        procs.diffctl(
            "spawn",
            "controller",
            "jsb2",
            "jsb3",
            "--activate-as-group",
            "--switch-timeout",
            "10",
            "-c",
            "my_ctrl_mgr",
            "-p",
            str(tmp_path / "a.yaml"),
            "--param-file",
            str(tmp_path / "b.yaml"),
        )
    )
    assert code == 0, out
    assert (cm.controller_state("jsb2"), cm.controller_state("jsb3")) == ("active", "active")

    # --inactive: loaded and configured, not activated.
    code, out = finish(
        procs.diffctl(
            "spawn",
            "controller",
            "jsb4",
            "--inactive",
            "-c",
            "my_ctrl_mgr",
            "-t",
            "joint_state_broadcaster/JointStateBroadcaster",
        )
    )
    assert code == 0, out
    assert cm.controller_state("jsb4") == "inactive"
