"""The manager's services over a real router, the spawner's flow and exit codes, and the `diffctl control` verbs."""

from __future__ import annotations

import signal
import subprocess
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SDF = REPO / "description" / "my_diff_car_control.sdf"
CONFIG = REPO / "config" / "diff_drive_controller.yaml"

FORWARD_YAML = """
wheels_forward:
  ros__parameters:
    type: velocity_controllers/JointGroupVelocityController
    joints: [base_link_to_left_wheel, base_link_to_right_wheel]
"""


def run(procs, *args: str, timeout_s: float = 20.0) -> tuple[int, str]:
    p = procs.diffctl(*args)
    out, _ = p.communicate(timeout=timeout_s)
    return p.returncode, out


def wait_for_log(pred, timeout_s: float = 10.0) -> None:
    deadline = time.monotonic() + timeout_s
    while not pred():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.05)


@pytest.mark.slow
def test_services_appear_with_the_description_and_serve_every_verb(router, procs, tmp_path, monkeypatch) -> None:
    from diffctl.client import runtime
    from diffctl.client.signals import SignalHandlerOptions

    monkeypatch.setenv("ROS_HOME", str(tmp_path))
    runtime.init(args=["test_services"], signal_handler_options=SignalHandlerOptions.NO)
    try:
        _services_and_verbs(procs, tmp_path)
    finally:
        runtime.try_shutdown()


def _services_and_verbs(procs, tmp_path: Path) -> None:
    from diffctl.client.interfaces import cls
    from diffctl.client.node import Node
    from diffctl.client.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
    from diffctl.control.cm_client import ManagerClient

    log = tmp_path / "manager.log"
    cm_proc = procs.diffctl(
        "control",
        "manager",
        "--param-file",
        str(CONFIG),
        "--hardware-plugin",
        "mock_components/GenericSystem",
        "--ros-args",
        "-p",
        "use_sim_time:=false",
        "-p",
        "update_rate:=50",
        # a rule of the manager's own command line, for one of the nodes it hosts (rcl's node-prefixed remap)
        "-r",
        "diffbot_base_controller:~/cmd_vel:=/remapped_cmd_vel",
        stdout=log.open("w"),
        stderr=subprocess.STDOUT,
    )
    node = Node("test_cm_client")
    cm = ManagerClient(node)
    # Jazzy: no services until a robot_description arrives; the manager says it is waiting.
    wait_for_log(lambda: "Waiting for data on 'robot_description'" in log.read_text())
    assert not cm.client("list_controllers").wait_for_service(timeout_sec=0.5)
    latched = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    desc = node.create_publisher(cls("std_msgs/msg/String"), "/robot_description", latched)
    desc.publish(cls("std_msgs/msg/String")(data=SDF.read_text()))
    cm.wait("list_controllers", 10.0)
    # ~/activity: transient local, so this late subscriber still gets the state the manager came up with
    # (its callback runs while the client spins the node for its calls).
    activity: list = []
    node.create_subscription(cls("controller_manager_msgs/msg/ControllerManagerActivity"),
                             "/controller_manager/activity", activity.append, latched)

    def wait_for(pred, timeout_s: float = 10.0) -> None:
        deadline = time.monotonic() + timeout_s
        while not pred():
            assert time.monotonic() < deadline, "timed out"
            cm._executor.spin_once(timeout_sec=0.05)

    def last_activity() -> tuple[dict[str, str], dict[str, str]]:
        a = activity[-1]
        return ({c.name: c.state.label for c in a.controllers}, {h.name: h.state.label for h in a.hardware_components})

    wait_for(lambda: activity)
    assert last_activity() == ({}, {"robot": "active"})

    types_ = cm.call("list_controller_types")
    assert "diff_drive_controller/DiffDriveController" in types_.types
    comps = cm.call("list_hardware_components").component
    assert [(c.name, c.plugin_name, c.state.label, c.rw_rate) for c in comps] == [
        ("robot", "mock_components/GenericSystem", "active", 50)
    ]
    ifaces = cm.call("list_hardware_interfaces")
    assert sorted(i.name for i in ifaces.command_interfaces) == [
        "base_link_to_left_wheel/velocity",
        "base_link_to_right_wheel/velocity",
    ]
    assert len(ifaces.state_interfaces) == 4 and all(i.is_available for i in ifaces.state_interfaces)
    assert {i.data_type for i in [*ifaces.command_interfaces, *ifaces.state_interfaces]} == {"double"}

    # Spawner: type and params_file come from --param-file; exit 0; a second run skips the load and still exits 0.
    rc, out = run(procs, "spawn", "controller", "diffbot_base_controller", "-p", str(CONFIG))
    assert rc == 0 and "Configured and activated diffbot_base_controller" in out, out
    rc, out = run(procs, "spawn", "controller", "diffbot_base_controller", "-p", str(CONFIG))
    assert rc == 0 and "Controller already loaded, skipping load_controller" in out, out
    (ctrl,) = cm.list_controllers()
    assert (ctrl.state, ctrl.type, ctrl.update_rate) == ("active", "diff_drive_controller/DiffDriveController", 50)
    assert sorted(ctrl.claimed_interfaces) == ["base_link_to_left_wheel/velocity", "base_link_to_right_wheel/velocity"]
    wait_for(lambda: last_activity()[0] == {"diffbot_base_controller": "active"})
    wait_for(lambda: node.count_subscribers("/remapped_cmd_vel"))
    assert not node.count_subscribers("/diffbot_base_controller/cmd_vel")

    # Failures exit 1 with the reason.
    rc, out = run(procs, "spawn", "controller", "no_such_controller")
    assert rc == 1 and "Failed loading controller no_such_controller" in out
    assert "'type' param was not defined for 'no_such_controller'" in log.read_text()
    rc, out = run(procs, "spawn", "controller", "x", "-p", str(tmp_path / "missing.yaml"))
    assert rc == 1 and "does not exist" in out
    rc, out = run(procs, "spawn", "controller", "x", "-c", "/elsewhere", "--controller-manager-timeout", "0.5")
    assert rc == 1 and "Could not contact service /elsewhere/list_controllers" in out
    fwd = tmp_path / "forward.yaml"
    fwd.write_text(FORWARD_YAML)
    rc, out = run(procs, "spawn", "controller", "wheels_forward", "-p", str(fwd))
    assert rc == 1 and "Failed to activate controller wheels_forward" in out
    assert "currently claimed by another controller 'diffbot_base_controller'" in out

    # The verbs: tables and state changes through the same services.
    rc, out = run(procs, "control", "list_controllers")
    assert rc == 0 and "diffbot_base_controller" in out and "wheels_forward" in out and "inactive" in out
    rc, out = run(
        procs,
        "control",
        "switch_controllers",
        "--deactivate",
        "diffbot_base_controller",
        "--activate",
        "wheels_forward",
        "--strict",
    )
    assert rc == 0, out
    assert {c.name: c.state for c in cm.list_controllers()} == {
        "diffbot_base_controller": "inactive",
        "wheels_forward": "active",
    }
    rc, out = run(procs, "control", "switch_controllers", "--activate", "ghost", "--strict")
    assert rc == 1 and "Aborting, no controller is switched!" in out
    rc, out = run(procs, "control", "unload_controller", "wheels_forward")
    assert rc == 1  # still active
    rc, out = run(procs, "control", "set_controller_state", "wheels_forward", "inactive")
    assert rc == 0, out
    rc, out = run(procs, "control", "cleanup_controller", "wheels_forward")
    assert rc == 0, out
    rc, out = run(procs, "control", "unload_controller", "wheels_forward")
    assert rc == 0, out
    rc, out = run(procs, "control", "set_hardware_component_state", "robot", "inactive")
    assert rc == 0, out
    wait_for(lambda: last_activity()[1] == {"robot": "inactive"})
    rc, out = run(procs, "control", "list_hardware_interfaces", "-v")
    assert rc == 0 and "no" in out and "double" in out
    rc, out = run(procs, "control", "set_controller_state", "diffbot_base_controller", "active")
    assert rc == 1 and "not available" in out
    rc, out = run(procs, "control", "set_hardware_component_state", "robot", "active")
    assert rc == 0, out
    rc, out = run(procs, "control", "load_controller", "jsb2", "--set-state", "active")
    assert rc == 1  # no jsb2.type anywhere

    # -u: the spawner stays up and, on SIGTERM, deactivates and unloads what it spawned, exiting 0.
    p = procs.diffctl("spawn", "controller", "joint_state_broadcaster", "-u")
    wait_for(lambda: cm.controller_state("joint_state_broadcaster") == "active")
    p.send_signal(signal.SIGTERM)
    out, _ = p.communicate(timeout=10)
    assert p.returncode == 0, out
    assert cm.controller_state("joint_state_broadcaster") is None
    cm.close()
    node.destroy_node()
    assert procs.stop(cm_proc) == 0
