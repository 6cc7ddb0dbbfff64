"""The controller manager's `enforce_command_limits` on mock hardware (a diff-drive base with an arm), controllers
on real client nodes: off (Jazzy's default) a command reaches the hardware as the controller wrote it; on, the
resource manager bounds it by the robot description's joint limits as ros2_control computes them."""

from __future__ import annotations

import pytest
from control_fakes import loaded, make_manager

from diffctl.control.lifecycle import State
from diffctl.control.robot_hardware import hardware_infos
from diffctl.control.switching import STRICT

pytestmark = pytest.mark.usefixtures("client_bus")

WHEEL_LIMIT = 2.0  # rad/s, the wheels' URDF <limit velocity>
ARM_SPEED = 0.5  # rad/s, the arm's
PERIOD_S = 0.01  # update_rate 100
ROBOT = f"""<robot name="diffbot_arm"><link name="base_link"/><link name="left"/><link name="right"/><link name="arm"/>
<joint name="left_wheel_joint" type="continuous"><parent link="base_link"/><child link="left"/><axis xyz="0 1 0"/>
  <limit effort="5" velocity="{WHEEL_LIMIT}"/></joint>
<joint name="right_wheel_joint" type="continuous"><parent link="base_link"/><child link="right"/><axis xyz="0 1 0"/>
  <limit effort="5" velocity="{WHEEL_LIMIT}"/></joint>
<joint name="arm_joint" type="revolute"><parent link="base_link"/><child link="arm"/><axis xyz="0 0 1"/>
  <limit lower="-1" upper="1" effort="10" velocity="{ARM_SPEED}"/></joint>
<ros2_control name="DiffBotArm" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
  <joint name="left_wheel_joint"><command_interface name="velocity"/><state_interface name="position"/>
    <state_interface name="velocity"/></joint>
  <joint name="right_wheel_joint"><command_interface name="velocity"/><state_interface name="position"/>
    <state_interface name="velocity"/></joint>
  <joint name="arm_joint"><command_interface name="position"/>
    <state_interface name="position"><param name="initial_value">ARM_START</param></state_interface></joint>
</ros2_control></robot>"""
WHEELS = ["left_wheel_joint/velocity", "right_wheel_joint/velocity"]


def manager(enforce: bool, arm_start_rad: float = 0.0, **controllers: dict):
    robot = ROBOT.replace("ARM_START", str(arm_start_rad))
    cm, log = make_manager(controllers, hardware=hardware_infos(robot), robot_description=robot,
                           enforce_command_limits=enforce)
    loaded(cm, *controllers)
    assert cm.switch_controller(list(controllers), [], STRICT) == (True, "")
    return cm, log


def run(cm, cycles: int) -> None:
    for i in range(cycles):
        cm.cycle((i + 1) * 10_000_000, PERIOD_S)


@pytest.mark.parametrize("enforce", [False, True])
def test_wheel_commands_past_the_urdf_limit_are_clamped_only_when_enforcing(enforce: bool) -> None:
    cm, log = manager(enforce, drive={"commands": WHEELS, "command_value": 10.0})
    run(cm, 3)
    speeds = [cm.state_value(n) for n in WHEELS]  # the mock mirrors the commands it got
    limited = "Command of at least one joint is out of limits (throttled log)"
    if enforce:
        assert speeds == [WHEEL_LIMIT, WHEEL_LIMIT]
        assert "Enforcing command limits is enabled..." in log.text("INFO")
        assert (f"{limited}. Joint: 'left_wheel_joint', (actual: [Joint: 'left_wheel_joint', position: 0.000000, "
                "velocity: 0.000000], command: [Joint: 'left_wheel_joint', velocity: 10.000000], limited: [Joint: "
                "'left_wheel_joint', velocity: 2.000000]) with desired period : 0.010000 sec.") in log.text("ERROR")
    else:
        assert speeds == [10.0, 10.0]
        assert "Enforcing command limits is disabled. Command limits from URDF will be ignored." in log.text("INFO")
        assert limited not in log.text()


def test_position_commands_advance_at_the_joints_speed_limit_and_a_joint_past_its_limit_fails_its_controller() -> None:
    cm, _ = manager(True, arm={"commands": ["arm_joint/position"], "command_value": 3.0})
    run(cm, 10)
    # each period one step of max_velocity × dt from the previous (limited) command, from the measured 0 rad;
    # the mock's state is the command of the cycle before
    step = ARM_SPEED * PERIOD_S
    assert cm.rm.command_interfaces["arm_joint/position"].value == pytest.approx(10 * step)
    assert cm.state_value("arm_joint/position") == pytest.approx(9 * step)
    # measured 1.5 rad, past the upper limit of 1 rad by more than the 0.0087 rad tolerance: the controller's
    # command raises in the resource manager, as in ros2_control, and the controller is deactivated
    cm, log = manager(True, arm_start_rad=1.5, arm={"commands": ["arm_joint/position"], "command_value": 0.0})
    run(cm, 1)
    assert cm.controllers["arm"].state is State.INACTIVE
    assert ("Joint position is out of bounds for the joint : 'arm_joint' actual position: 1.5 limits: [-1.0, 1.0]"
            in log.text("ERROR"))
