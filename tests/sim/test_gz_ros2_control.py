"""The controller manager inside the simulator (gz_ros2_control): its hardware on real PyBullet joints, and
the manager hosted by a real simulation on a real router, stepped on sim time."""

from __future__ import annotations

import math
import time
from dataclasses import replace
from pathlib import Path
from typing import Any

import pybullet as pb
import pytest
from sim_helpers import CAR_CONTROL, EMPTY_WORLD, LEFT, REPO, RIGHT, car_world

from diffctl.control.controller_interface import ReturnType
from diffctl.control.hardware_interface import InterfaceInfo
from diffctl.control.robot_hardware import infos_from_blocks
from diffctl.description.pose import Pose
from diffctl.description.sdf_loader import load_world, parse_model
from diffctl.errors import ConfigError, DescriptionError
from diffctl.sim.plugins.gazebo_sim_system import GazeboSimSystem
from diffctl.sim.plugins.gz_ros2_control import GzRos2ControlParams

CONTROLLERS = REPO / "config" / "diff_drive_controller.yaml"


def control_text(params_file: Path | str = CONTROLLERS, extra_plugin_xml: str = "") -> str:
    text = CAR_CONTROL.read_text().replace("PARAMETERS_CONFIG_FILE_PLACEHOLDER", str(params_file))
    if extra_plugin_xml:
        text = text.replace("</parameters>", "</parameters>" + extra_plugin_xml, 1)
    return text


def bound_system(
    hold: bool = True, limits: dict[str, tuple[float, float]] | None = None, airborne: bool = False
) -> tuple[Any, Any, Any]:
    pw, car = car_world(pose=Pose.from_xyz_rpy((0, 0, 5.0)) if airborne else None, path=CAR_CONTROL)
    info = infos_from_blocks(car.model.ros2_control, str(CAR_CONTROL))[0]
    if limits:
        joints = []
        for j in info.joints:
            cmds = tuple(
                InterfaceInfo(c.name, *limits[j.name]) if j.name in limits else c for c in j.command_interfaces
            )
            joints.append(replace(j, command_interfaces=cmds))
        info = replace(info, joints=tuple(joints))
    hw = GazeboSimSystem().bind(car, hold_joints=hold, position_proportional_gain=0.1)
    hw.update_rate = 20
    hw.on_init(info)
    hw.export_state_interfaces()
    hw.export_command_interfaces()
    return pw, car, hw


def run(pw: Any, hw: Any, steps: int) -> None:
    for _ in range(steps):
        hw.step()
        pw.step()


def wheel_velocity(car: Any, joint: str) -> float:
    return car.joint_states([car.joint(joint)])[0][1]


def test_outside_the_simulator_it_is_a_clear_error() -> None:
    _pw, car = car_world(path=CAR_CONTROL)
    info = infos_from_blocks(car.model.ros2_control, str(CAR_CONTROL))[0]
    with pytest.raises(ConfigError, match="runs only inside the simulator") as e:
        GazeboSimSystem().on_init(info)
    assert "mock_components/GenericSystem" in str(e.value.hint)


def test_a_joint_the_model_does_not_have_is_refused() -> None:
    _pw, car = car_world(path=CAR_CONTROL)
    info = infos_from_blocks(car.model.ros2_control, str(CAR_CONTROL))[0]
    bad = replace(info, joints=(replace(info.joints[0], name="no_such_joint"),))
    with pytest.raises(DescriptionError, match="no_such_joint"):
        GazeboSimSystem().bind(car, hold_joints=True, position_proportional_gain=0.1).on_init(bad)


def test_velocity_commands_drive_the_joints_and_states_follow() -> None:
    pw, _car, hw = bound_system()
    assert hw.prepare_command_mode_switch([f"{LEFT}/velocity", f"{RIGHT}/velocity"], [])
    hw.perform_command_mode_switch([f"{LEFT}/velocity", f"{RIGHT}/velocity"], [])
    hw.commands[f"{LEFT}/velocity"].value = 5.0
    hw.commands[f"{RIGHT}/velocity"].value = -5.0
    assert hw.write(0, 0.05) is ReturnType.OK
    run(pw, hw, 300)
    assert hw.read(0, 0.05) is ReturnType.OK
    assert hw.states[f"{LEFT}/velocity"].value == pytest.approx(5.0, rel=0.02)
    assert hw.states[f"{RIGHT}/velocity"].value == pytest.approx(-5.0, rel=0.02)
    assert hw.states[f"{LEFT}/position"].value > 1.0  # turned ~1.5 rad in 0.3 s


def test_nan_holds_infinity_never_reaches_the_physics_and_interface_limits_do_not_clamp() -> None:
    # gz_system.cpp (Jazzy) writes the command as it is: an interface's min/max only become joint limits when the
    # controller manager's enforce_command_limits (default false) imports limiters.
    pw, car, hw = bound_system(limits={LEFT: (-2.0, 2.0)})
    hw.perform_command_mode_switch([f"{LEFT}/velocity", f"{RIGHT}/velocity"], [])
    hw.commands[f"{LEFT}/velocity"].value = 10.0  # past the interface's max of 2
    hw.commands[f"{RIGHT}/velocity"].value = math.inf
    hw.write(0, 0.05)
    run(pw, hw, 300)
    assert wheel_velocity(car, LEFT) == pytest.approx(10.0, rel=0.02)
    assert abs(wheel_velocity(car, RIGHT)) < 0.05  # held, not spun up
    hw.commands[f"{LEFT}/velocity"].value = math.nan
    hw.write(0, 0.05)
    run(pw, hw, 300)
    assert abs(wheel_velocity(car, LEFT)) < 0.05


def test_idle_joints_are_held_or_free_as_hold_joints_says() -> None:
    for hold in (True, False):
        pw, car, hw = bound_system(hold=hold, airborne=True)  # no ground contact to slow a free wheel
        h = car.joint(LEFT)
        pb.resetJointState(h.body, h.index, 0.0, 8.0, physicsClientId=car.client)  # spin it by hand
        hw.write(0, 0.05)
        run(pw, hw, 50)
        v = abs(wheel_velocity(car, LEFT))
        assert (v < 0.05) if hold else (v > 2.0), (hold, v)


def test_position_and_effort_modes_are_applied_every_step() -> None:
    pw, car, hw = bound_system()
    # The tutorial's wheels only export velocity; give them position/effort handles as other robots do.
    hw.commands[f"{LEFT}/position"] = type(hw.commands[f"{LEFT}/velocity"])(f"{LEFT}/position", 1.0)
    hw.commands[f"{RIGHT}/effort"] = type(hw.commands[f"{RIGHT}/velocity"])(f"{RIGHT}/effort", 0.05)
    hw.perform_command_mode_switch([f"{LEFT}/position", f"{RIGHT}/effort"], [])
    hw.write(0, 0.05)
    run(pw, hw, 3000)
    assert car.joint_states([car.joint(LEFT)])[0][0] == pytest.approx(1.0, abs=0.05)  # P law: -Kp (q - q*) rate
    assert car.joint_states([car.joint(RIGHT)])[0][0] > 1.0  # a steady torque spins the free wheel up


def test_plugin_elements_are_read_with_their_defaults_and_errors() -> None:
    ns = (
        "<ros><namespace>robot1</namespace><remapping>/a:=/b</remapping>"
        "<remapping>--ros-args -r c:=d</remapping></ros><controller_manager_name>cm</controller_manager_name>"
    )
    model = parse_model(control_text(extra_plugin_xml=ns), source="test")
    plugin = next(p for p in model.plugins if p.system == "gz_ros2_control")
    p = GzRos2ControlParams.from_plugin(plugin, "test")
    assert p.parameters == (str(CONTROLLERS),)
    assert p.namespace == "/robot1" and p.remappings == (("/a", "/b"), ("c", "d"))
    assert p.controller_manager_name == "cm" and p.hold_joints and p.position_proportional_gain == 0.1
    placeholder = parse_model(CAR_CONTROL.read_text(), source="test")
    with pytest.raises(DescriptionError, match="PARAMETERS_CONFIG_FILE_PLACEHOLDER"):
        GzRos2ControlParams.from_plugin(next(p for p in placeholder.plugins if p.system == "gz_ros2_control"), "t")
    bad = parse_model(control_text(extra_plugin_xml="<ros><remapping>nonsense</remapping></ros>"), source="test")
    with pytest.raises(DescriptionError, match="from:=to"):
        GzRos2ControlParams.from_plugin(next(p for p in bad.plugins if p.system == "gz_ros2_control"), "t")


# --- hosted by a simulation, on a real router ---------------------------------------------------------


def step(sim: Any, n: int) -> None:
    """Step the world `n` times on this thread, as the sim thread does."""
    st = sim.stepper
    st.drain()
    for _ in range(n):
        for h in st.step_hooks:
            h()
        sim.physics.step()
        st.sim_time_ns += st.step_ns
        st.run_due()


def run_until(sim: Any, pred: Any, timeout_s: float = 20.0, what: str = "condition") -> None:
    """Step the world until `pred()` holds."""
    deadline = time.monotonic() + timeout_s
    while not pred():
        assert time.monotonic() < deadline, f"timed out waiting for {what}"
        step(sim, 20)


def test_the_simulation_hosts_a_manager_that_drives_the_car(router: str) -> None:
    import threading

    from diffctl.bus import open_session
    from diffctl.sim.runner import Simulation
    from tests.probe import Probe

    session = open_session()
    sim = Simulation(load_world(EMPTY_WORLD), rtf=0, paused=True, session=session)
    client = Probe("test_client")
    try:
        text = control_text()
        sim.spawn(parse_model(text, source="robot_description", name="robot"), text)
        rt = sim.models["robot"]
        assert rt.control is not None and rt.control.node.get_fully_qualified_name() == "/controller_manager"
        cm = rt.control.cm
        assert [i.plugin_name for i in rt.control.infos] == ["gz_ros2_control/GazeboSimSystem"]
        # The manager's services answer over the bus, as the standalone manager's do.
        listing = client.create_client(
            "/controller_manager/list_hardware_components", "controller_manager_msgs/srv/ListHardwareComponents"
        )
        assert listing.wait_for_service(10.0)
        comps = listing.call({}, timeout=10.0).component
        assert [(c.name, c.plugin_name, c.state.label) for c in comps] == [
            ("robot", "gz_ros2_control/GazeboSimSystem", "active")
        ]
        # As the spawner does with --param-file: the diff drive's type is in its own section of the file.
        cm.load_controller("diffbot_base_controller", "diff_drive_controller/DiffDriveController")
        cm.load_controller("joint_state_broadcaster")
        for name in ("diffbot_base_controller", "joint_state_broadcaster"):
            cm.configure_controller(name)
        # A switch is carried out by the simulator's next control cycle: step the world while waiting for it.
        result: list[tuple[bool, str]] = []
        t = threading.Thread(
            target=lambda: result.append(
                cm.switch_controller(["diffbot_base_controller", "joint_state_broadcaster"], [], timeout_s=30.0)
            )
        )
        t.start()
        run_until(sim, lambda: bool(result), what="the switch")
        t.join()
        assert result[0][0], result
        odom: list[Any] = []
        client.create_subscription("/diffbot_base_controller/odom", "nav_msgs/msg/Odometry", odom.append)
        cmd = client.create_publisher("/diffbot_base_controller/cmd_vel", "geometry_msgs/msg/TwistStamped")
        x0 = rt.entity.pose().xyz[0]
        t0 = sim.stepper.sim_time_ns
        while sim.stepper.sim_time_ns - t0 < 2_000_000_000:  # 2 s of sim time at 0.5 m/s, commands at 20 Hz
            # Stamped zero ("now"): no bridge carries /clock here; the controller's clock is the manager's.
            cmd.publish({"twist": {"linear": {"x": 0.5}}})
            time.sleep(0.005)
            step(sim, 20)
        assert rt.entity.pose().xyz[0] - x0 > 0.5
        assert odom and odom[-1].header.stamp.sec >= 1  # stamped with sim time
        assert odom[-1].pose.pose.position.x > 0.5
    finally:
        client.close()
        sim.close()
