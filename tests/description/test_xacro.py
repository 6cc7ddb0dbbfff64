"""xacro through the real `xacro` package: `$(find)` via diffctl's package index, in-process and as the command.

Oracle: the `xacro` executable of the venv (the PyPI package's own CLI), whose `$(find)` reaches diffctl's index
through the `ament_index_python` package diffctl ships.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from diffctl.description.robot_files import load_description, read_description_text
from diffctl.description.urdf.xacro_runner import process_xacro
from diffctl.errors import DescriptionError

XACRO_EXE = Path(sys.executable).parent / "xacro"

ROBOT = """<?xml version="1.0"?>
<robot name="demo_bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="use_sim" default="true"/>
  <xacro:arg name="prefix" default=""/>
  <xacro:property name="wheel_radius" value="0.04"/>
  <xacro:include filename="$(find demo_bot)/urdf/wheel.xacro"/>
  <link name="$(arg prefix)base_link">
    <inertial><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.02"/></inertial>
    <collision><geometry><box size="0.3 0.2 0.05"/></geometry></collision>
  </link>
  <xacro:wheel side="left" y="0.15"/>
  <xacro:wheel side="right" y="-0.15"/>
  <xacro:if value="$(arg use_sim)">
    <gazebo>
      <plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">
        <parameters>$(find demo_bot)/config/controllers.yaml</parameters>
      </plugin>
    </gazebo>
  </xacro:if>
</robot>
"""

WHEEL = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="wheel" params="side y">
    <link name="${side}_wheel">
      <inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
      <collision><geometry><cylinder radius="${wheel_radius}" length="0.02"/></geometry></collision>
    </link>
    <joint name="${side}_wheel_joint" type="continuous">
      <parent link="base_link"/><child link="${side}_wheel"/>
      <origin xyz="0 ${y} 0" rpy="${-pi/2} 0 0"/><axis xyz="0 0 1"/>
    </joint>
  </xacro:macro>
</robot>
"""


@pytest.fixture
def install(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """An install tree holding package demo_bot, on AMENT_PREFIX_PATH; returns its share directory."""
    prefix = tmp_path / "install"
    share = prefix / "share" / "demo_bot"
    (share / "urdf").mkdir(parents=True)
    (share / "config").mkdir()
    markers = prefix / "share" / "ament_index" / "resource_index" / "packages"
    markers.mkdir(parents=True)
    (markers / "demo_bot").write_text("")
    (share / "package.xml").write_text("<package format='3'><name>demo_bot</name></package>")
    (share / "urdf" / "robot.urdf.xacro").write_text(ROBOT)
    (share / "urdf" / "wheel.xacro").write_text(WHEEL)
    (share / "config" / "controllers.yaml").write_text("controller_manager:\n  ros__parameters:\n    update_rate: 50\n")
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(prefix))
    monkeypatch.chdir(tmp_path)
    return share


def _run_xacro_command(args: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PATH": f"{XACRO_EXE.parent}{os.pathsep}{os.environ.get('PATH', '')}"}
    return subprocess.run([str(XACRO_EXE), *args], capture_output=True, text=True, timeout=120, cwd=cwd, env=env)


def test_in_process_expansion_equals_the_xacro_command(install: Path) -> None:
    path = install / "urdf" / "robot.urdf.xacro"
    run = _run_xacro_command([str(path), "prefix:=my_"], install)
    assert run.returncode == 0, run.stderr
    ours = process_xacro(path, {"prefix": "my_"})
    assert ours == run.stdout
    assert f"<parameters>{install}/config/controllers.yaml</parameters>" in ours
    assert '<link name="my_base_link">' in ours


def test_xacro_file_loads_as_a_simulated_model(install: Path) -> None:
    model = load_description(install / "urdf" / "robot.urdf.xacro")
    assert [link.name for link in model.links] == ["base_link", "left_wheel", "right_wheel"]
    assert model.link("left_wheel").collisions[0].geometry.radius_m == 0.04
    (plugin,) = model.plugins
    assert plugin.system == "gz_ros2_control"
    assert plugin.get("parameters") == str(install / "config" / "controllers.yaml")
    # name:=value arguments reach xacro:arg, as on the command line
    without = load_description(install / "urdf" / "robot.urdf.xacro", mappings={"use_sim": "false"})
    assert without.plugins == ()


def test_expanded_text_has_no_xacro_left(install: Path) -> None:
    text = read_description_text(install / "urdf" / "robot.urdf.xacro")
    assert "<xacro:" not in text and "${" not in text and "$(find" not in text


def _error(path: Path, **mappings: str) -> DescriptionError:
    with pytest.raises(DescriptionError) as info:
        process_xacro(path, mappings)
    err = info.value
    assert err.exit_code == 2
    assert "\n" not in str(err)
    return err


def test_undefined_property_in_an_included_file_names_that_file_and_line(install: Path) -> None:
    wheel = install / "urdf" / "wheel.xacro"
    wheel.write_text(WHEEL.replace("${wheel_radius}", "${wheel_radiu}"))
    err = _error(install / "urdf" / "robot.urdf.xacro")
    assert err.source == str(wheel)
    assert err.line == 6
    assert "wheel_radiu" in err.message
    assert err.hint == f"in macro 'wheel', used in {install / 'urdf' / 'robot.urdf.xacro'}"


def test_unknown_package_in_find(install: Path) -> None:
    path = install / "urdf" / "robot.urdf.xacro"
    path.write_text(ROBOT.replace("$(find demo_bot)/urdf", "$(find demo_bots)/urdf"))
    err = _error(path)
    assert err.source == str(path) and err.line == 6
    assert "demo_bots" in err.message and "not found" in err.message


def test_missing_argument_and_malformed_xml(install: Path) -> None:
    path = install / "urdf" / "robot.urdf.xacro"
    path.write_text(ROBOT.replace('<xacro:arg name="prefix" default=""/>', ""))
    err = _error(path)
    assert err.line == 7 and "prefix" in err.message
    path.write_text(ROBOT.replace("</link>", "</lnk>", 1))
    err = _error(path)
    assert err.source == str(path) and err.line == 10 and "malformed XML" in err.message


def test_the_xacro_command_reports_an_unknown_package(install: Path) -> None:
    path = install / "urdf" / "robot.urdf.xacro"
    path.write_text(ROBOT.replace("$(find demo_bot)/urdf", "$(find demo_bots)/urdf"))
    run = _run_xacro_command([str(path)], install)
    assert run.returncode == 2
    assert "demo_bots" in run.stderr and "not found" in run.stderr
