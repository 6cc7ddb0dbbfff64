"""Manager parameters, controller parameter merging, the <ros2_control> block, mock hardware and the loop timer."""

from __future__ import annotations

import itertools
import math
import os
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from control_fakes import RecordingLog, wheel_info

from diffctl.control.controller_interface import ReturnType
from diffctl.control.hardware.generic_system import GenericSystem
from diffctl.control.params import load_manager_files, manager_params, section_type
from diffctl.control.realtime_loop import LoopStats, WallTicker, run
from diffctl.control.robot_hardware import PLACEHOLDER, hardware_infos, parameter_files
from diffctl.errors import DescriptionError, ParameterError

REPO = Path(__file__).resolve().parents[2]
CONFIG = REPO / "config" / "diff_drive_controller.yaml"
SDF = REPO / "description" / "my_diff_car_control.sdf"


def test_the_tutorial_yaml_configures_the_manager() -> None:
    p = manager_params(load_manager_files([str(CONFIG)]))
    assert (p.update_rate, p.use_sim_time) == (20, True)
    assert p.controllers["joint_state_broadcaster"].type == "joint_state_broadcaster/JointStateBroadcaster"
    assert "diffbot_base_controller" not in p.controllers  # its type comes through the spawner's --param-file
    assert section_type(str(CONFIG), "diffbot_base_controller") == "diff_drive_controller/DiffDriveController"


@pytest.mark.parametrize(
    ("flat", "field", "quoted"),
    [
        ({"update_rate": 0}, "update_rate", "0"),
        ({"update_rate": "fast"}, "update_rate", "'fast'"),
        ({"update_rate": 2.5}, "update_rate", "2.5"),
        ({"use_sim_time": "yes"}, "use_sim_time", "'yes'"),
        ({"defaults.switch_controller.strictness": "strikt"}, "defaults.switch_controller.strictness", "'strict'"),
        ({"thread_priority": 120}, "thread_priority", "120"),
        ({"x.type": "nonsense"}, "x.type", "'nonsense'"),
        ({"x.params_file": 3}, "x.params_file", "3"),
    ],
)
def test_bad_manager_parameters_are_refused_with_the_value(flat, field, quoted) -> None:
    with pytest.raises(ParameterError) as e:
        manager_params(flat, source="cm.yaml")
    assert e.value.field == field and quoted in str(e.value) and "cm.yaml" in str(e.value)


def test_launch_text_booleans() -> None:
    assert manager_params({"use_sim_time": "false"}).use_sim_time is False


def test_the_control_sdf_gives_one_hardware_block() -> None:
    (info,) = hardware_infos(SDF.read_text(), str(SDF))
    assert (info.name, info.type, info.plugin_name) == ("robot", "system", "gz_ros2_control/GazeboSimSystem")
    assert {j.name for j in info.joints} == {"base_link_to_left_wheel", "base_link_to_right_wheel"}
    for j in info.joints:
        assert [c.name for c in j.command_interfaces] == ["velocity"]
        assert [s.name for s in j.state_interfaces] == ["position", "velocity"]
    (mock,) = hardware_infos(
        SDF.read_text(), plugin_override="mock_components/GenericSystem", extra_params={"calculate_dynamics": "true"}
    )
    assert mock.plugin_name == "mock_components/GenericSystem"
    assert mock.hardware_parameters["calculate_dynamics"] == "true"
    files, problems = parameter_files(SDF.read_text())
    assert files == [] and PLACEHOLDER in problems[0]
    files, problems = parameter_files(SDF.read_text().replace(PLACEHOLDER, str(CONFIG)))
    assert files == [str(CONFIG)] and problems == []
    with pytest.raises(DescriptionError, match="no <ros2_control> block"):
        hardware_infos("<sdf version='1.9'><model name='m'/></sdf>", "m.sdf")


def _mock(**params: str) -> GenericSystem:
    hw = GenericSystem()
    hw.log = RecordingLog()
    hw.on_init(wheel_info(hw_params=params, commands=("velocity", "position"), initial_position=1.5))
    hw.export_state_interfaces()
    hw.export_command_interfaces()
    hw.on_configure()
    return hw


def test_generic_system_mirrors_commands() -> None:
    hw = _mock(position_state_following_offset="0.25")
    assert hw.states["left_wheel/position"].value == 1.5 and hw.states["left_wheel/velocity"].value == 0.0
    hw.commands["left_wheel/velocity"].set_value(2.0)
    assert hw.read(0, 0.01) is ReturnType.OK
    assert hw.states["left_wheel/velocity"].value == 2.0
    assert hw.states["left_wheel/position"].value == 1.5  # velocity mirrored, position untouched (as upstream)
    hw.commands["right_wheel/position"].set_value(3.0)
    hw.read(0, 0.01)
    assert hw.states["right_wheel/position"].value == 3.25
    hw.commands["left_wheel/velocity"].set_value(math.nan)
    hw.read(0, 0.01)
    assert hw.states["left_wheel/velocity"].value == 2.0  # NaN = no command
    hw.commands["left_wheel/velocity"].set_value(math.inf)
    assert hw.read(0, 0.01) is ReturnType.ERROR


def test_generic_system_integrates_with_calculate_dynamics() -> None:
    hw = _mock(calculate_dynamics="true")
    assert not hw.prepare_command_mode_switch(["left_wheel/velocity", "left_wheel/position"], [])
    assert hw.prepare_command_mode_switch(["left_wheel/velocity", "right_wheel/position"], [])
    hw.perform_command_mode_switch(["left_wheel/velocity", "right_wheel/position"], [])
    hw.commands["left_wheel/velocity"].set_value(2.0)
    hw.commands["right_wheel/position"].set_value(2.0)
    for _ in range(10):
        hw.read(0, 0.01)
    # Backward integration as upstream: the position moves by the previous velocity, so 9 of the 10 steps.
    assert hw.states["left_wheel/position"].value == pytest.approx(1.5 + 9 * 0.01 * 2.0)
    assert hw.states["left_wheel/velocity"].value == 2.0
    assert hw.states["right_wheel/position"].value == 2.0
    hw.perform_command_mode_switch([], ["left_wheel/velocity"])
    hw.read(0, 0.01)
    assert hw.states["left_wheel/position"].value == pytest.approx(1.68)  # no mode: no motion


def _mock_block(hw_params: dict[str, str], **joint_params: dict[str, str]) -> GenericSystem:
    from diffctl.control.hardware_interface import ComponentInfo, HardwareInfo, InterfaceInfo

    def joint(name: str) -> ComponentInfo:
        return ComponentInfo(
            name,
            command_interfaces=(InterfaceInfo("position"),),
            state_interfaces=(InterfaceInfo("position"), InterfaceInfo("velocity"), InterfaceInfo("actual")),
            parameters=joint_params.get(name, {}),
        )

    imu = ComponentInfo("imu", "sensor", state_interfaces=(InterfaceInfo("orientation.z"),))
    info = HardwareInfo(
        "arm", plugin_name="mock_components/GenericSystem", hardware_parameters=hw_params,
        joints=(joint("a"), joint("b")), sensors=(imu,), source="arm.urdf",
    )  # fmt: skip
    hw = GenericSystem()
    hw.on_init(info)
    hw.export_state_interfaces()
    hw.export_command_interfaces()
    hw.on_configure()
    return hw


def test_generic_system_disable_commands_mock_sensor_commands_offsets_and_mimic() -> None:
    log = RecordingLog()
    hw = _mock_block({"disable_commands": "true"})
    hw.log = log
    hw.commands["a/position"].set_value(1.0)
    assert hw.read(0, 0.01) is ReturnType.OK
    assert hw.states["a/position"].value == 0.0 and "Command propagation is disabled" in log.text("WARN")

    hw = _mock_block({"mock_sensor_commands": "true", "calculate_dynamics": "true"})
    assert "imu/orientation.z" in hw.commands  # a command interface for every sensor state
    hw.commands["imu/orientation.z"].set_value(0.7)
    hw.read(0, 0.01)
    assert hw.states["imu/orientation.z"].value == 0.7  # mirrored, with calculate_dynamics too
    assert "imu/orientation.z" not in _mock_block({}).commands

    hw = _mock_block({"position_state_following_offset": "0.5", "custom_interface_with_following_offset": "actual"})
    hw.commands["a/position"].set_value(1.0)
    hw.read(0, 0.01)
    assert (hw.states["a/position"].value, hw.states["a/actual"].value) == (1.0, 1.5)

    hw = _mock_block({}, b={"mimic": "a", "multiplier": "-2"})
    hw.commands["a/position"].set_value(0.25)
    hw.read(0, 0.01)
    assert hw.states["b/position"].value == -0.5
    with pytest.raises(ParameterError, match="mimicked joint 'c' not found"):
        _mock_block({}, b={"mimic": "c"})


def test_generic_system_refuses_bad_params() -> None:
    with pytest.raises(ParameterError, match=r"'maybe' is not a bool") as e:
        _mock(calculate_dynamics="maybe")
    assert "calculate_dynamics" in str(e.value)
    with pytest.raises(ParameterError, match="'abc' is not a finite number"):
        _mock(position_state_following_offset="abc")


def test_wall_ticker_counts_overruns_and_skips_missed_periods() -> None:
    stats = LoopStats()
    warnings: list[str] = []
    ticker = WallTicker(100, stats, warnings.append)
    stop = threading.Event()
    times: list[int] = []

    def cycle(t_ns: int, period_s: float) -> None:
        times.append(time.monotonic_ns())
        if len(times) == 5:
            time.sleep(0.035)  # three and a half periods late
        if len(times) == 15:
            stop.set()

    run(cycle, ticker, stop, stats)
    # Behaviour, not timing (a loaded machine may add overruns of its own): the late cycle is counted and
    # logged, and the loop goes back to its grid instead of bursting through the missed periods.
    assert stats.overruns >= 1 and "Overrun detected!" in warnings[0]
    gaps_ms = [(b - a) / 1e6 for a, b in itertools.pairwise(times)]
    assert gaps_ms[4] >= 35.0
    # On the grid again: the cycles after the late one start no earlier than their period boundaries, so they
    # span at least (n - 1) periods (a load that wakes one late only adds to that); a burst through the three
    # missed periods would squeeze three cycles into a few microseconds and fall ~30 ms short.
    after = gaps_ms[5:]
    assert sum(after) >= 10.0 * (len(after) - 1) - 1.0, f"catch-up burst after the overrun: {gaps_ms}"
    assert stats.summary(0.01)["cycles"] == 15


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--description", "nope.sdf"], "robot description file not found"),
        (["--description", str(SDF), "--hardware-plugin", "mock_components/GenericSystm"], "did you mean"),
        (["--description", str(SDF), "--param-file", "missing.yaml"], "parameter file not found"),
        (["--description", str(SDF), "--ros-args", "-p", "update_rate:=0"], "update_rate: 0 is not a valid rate"),
    ],
)
def test_manager_refuses_bad_input_before_starting(args: list[str], message: str, tmp_path) -> None:
    p = subprocess.run(
        [sys.executable, "-m", "diffctl", "control", "manager", *args],
        capture_output=True,
        text=True,
        timeout=30,
        cwd=tmp_path,
        env={**os.environ, "DIFFCTL_ROUTER": "tcp/127.0.0.1:9"},  # no router: nothing may start
    )
    assert p.returncode == 2 and message in p.stderr, p.stderr


USER_URDF = """<?xml version="1.0"?>
<robot name="real_bot">
  <link name="base_link"/><link name="wheel"/>
  <joint name="wheel_joint" type="continuous"><parent link="base_link"/><child link="wheel"/></joint>
  <ros2_control name="RealRobot" type="system">
    <hardware><plugin>diffdrive_arduino/DiffDriveArduinoHardware</plugin>
      <param name="device">/dev/ttyUSB0</param></hardware>
    <joint name="wheel_joint"><command_interface name="velocity"/><state_interface name="position"/></joint>
  </ros2_control>
</robot>
"""


def test_a_users_cpp_hardware_plugin_is_one_clear_line_suggesting_mock_hardware(tmp_path) -> None:
    urdf = tmp_path / "real_bot.urdf"
    urdf.write_text(USER_URDF)
    p = subprocess.run(
        [sys.executable, "-m", "diffctl", "control", "manager", "--description", str(urdf)],
        capture_output=True,
        text=True,
        timeout=30,
        cwd=tmp_path,
        env={**os.environ, "DIFFCTL_ROUTER": "tcp/127.0.0.1:9"},  # no router: nothing may start
    )
    lines = [line for line in p.stderr.splitlines() if line.strip()]
    assert p.returncode == 2 and len(lines) == 1, p.stderr
    assert "'diffdrive_arduino/DiffDriveArduinoHardware' is not available in diffctl" in lines[0]
    assert "mock_components/GenericSystem" in lines[0] and "use_mock_hardware:=true" in lines[0]


def test_the_resource_manager_names_the_block_and_file_of_an_unknown_plugin() -> None:
    from diffctl.control.resource_manager import ResourceManager
    from diffctl.errors import ConfigError

    info = wheel_info(name="RealRobot", plugin="my_robot_hardware/MyRobotSystem")
    info = type(info)(**{**info.__dict__, "source": "robot.urdf.xacro"})
    with pytest.raises(ConfigError) as e:
        ResourceManager().load(info)
    text = str(e.value)
    assert text.startswith("robot.urdf.xacro: <ros2_control name='RealRobot'>/hardware/plugin: ")
    assert "'my_robot_hardware/MyRobotSystem'" in text and "mock_components/GenericSystem" in text
    assert e.value.exit_code == 2
