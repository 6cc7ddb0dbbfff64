"""`diffctl description show FILE`: the SDF the simulator spawns for a URDF/xacro, faithful to what it loads.

The input is expanded by the real `xacro` package for comparison; the printed SDF, loaded again by the SDF
loader, must give the very model the simulator builds from the original file."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import xacro
from click.testing import CliRunner
from lxml import etree

from diffctl.cli.main import cli
from diffctl.description.robot_files import load_description
from diffctl.description.sdf_loader import parse_model

GRIPPER = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="gripper">
  <xacro:arg name="stroke" default="0.04"/>
  <xacro:property name="stroke" value="$(arg stroke)"/>
  <xacro:macro name="box_link" params="name mass x y z">
    <link name="${name}">
      <inertial><mass value="${mass}"/>
        <inertia ixx="${mass*(y*y+z*z)/12}" iyy="${mass*(x*x+z*z)/12}" izz="${mass*(x*x+y*y)/12}"
                 ixy="0" ixz="0" iyz="0"/></inertial>
      <collision><geometry><box size="${x} ${y} ${z}"/></geometry></collision>
    </link>
  </xacro:macro>
  <xacro:box_link name="palm" mass="0.5" x="0.1" y="0.2" z="0.05"/>
  <xacro:box_link name="pad" mass="0.05" x="0.02" y="0.2" z="0.01"/>
  <xacro:box_link name="left" mass="0.1" x="0.02" y="0.02" z="0.08"/>
  <xacro:box_link name="right" mass="0.1" x="0.02" y="0.02" z="0.08"/>
  <joint name="pad_joint" type="fixed"><parent link="palm"/><child link="pad"/><origin xyz="0 0 0.03"/></joint>
  <joint name="left_joint" type="prismatic">
    <parent link="palm"/><child link="left"/><origin xyz="0 0.05 -0.06"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="${stroke}" effort="20" velocity="0.2"/>
  </joint>
  <joint name="right_joint" type="prismatic">
    <parent link="palm"/><child link="right"/><origin xyz="0 -0.05 -0.06"/><axis xyz="0 1 0"/>
    <limit lower="${-stroke}" upper="0" effort="20" velocity="0.2"/>
    <mimic joint="left_joint" multiplier="-1" offset="0.001"/>
  </joint>
</robot>
"""


def write(tmp_path: Path) -> Path:
    path = tmp_path / "gripper.urdf.xacro"
    path.write_text(GRIPPER)
    return path


def test_show_prints_the_sdf_the_simulator_loads(tmp_path: Path) -> None:
    path = write(tmp_path)
    result = CliRunner().invoke(cli, ["description", "show", str(path), "stroke:=0.03"])
    assert result.exit_code == 0, result.output
    sdf = etree.fromstring(result.stdout.encode())
    assert sdf.tag == "sdf" and sdf.get("version") == "1.11"

    urdf = etree.fromstring(xacro.process_file(str(path), mappings={"stroke": "0.03"}).toprettyxml().encode())
    moving = {j.get("name"): j.get("type") for j in urdf.iter("joint") if j.get("type") != "fixed"}
    assert {j.get("name"): j.get("type") for j in sdf.iter("joint")} == moving  # the fixed pad was lumped
    limit = sdf.find(".//joint[@name='left_joint']/axis/limit")
    assert float(limit.findtext("upper")) == float(urdf.find(".//joint[@name='left_joint']/limit").get("upper"))
    mimic = sdf.find(".//joint[@name='right_joint']/axis/mimic")  # SDF 1.11's form of URDF's <mimic>
    assert mimic.get("joint") == "left_joint"
    assert (float(mimic.findtext("multiplier")), float(mimic.findtext("offset"))) == (-1.0, 0.001)

    shown = parse_model(result.stdout, base_dir=tmp_path)
    direct = load_description(path, mappings={"stroke": "0.03"})
    assert [(lk.name, lk.inertial) for lk in shown.links] == [(lk.name, lk.inertial) for lk in direct.links]
    assert shown.joints == direct.joints


def test_summary_lists_links_and_joints(tmp_path: Path) -> None:
    result = CliRunner().invoke(cli, ["description", "show", str(write(tmp_path)), "--summary"])
    assert result.exit_code == 0, result.output
    for name in ("palm", "left", "right", "left_joint", "right_joint"):
        assert name in result.stdout
    assert "pad_joint" not in result.stdout  # lumped, as Gazebo does


def test_bad_input_is_one_line_and_exit_2(tmp_path: Path) -> None:
    path = write(tmp_path)
    for args, expected in (
        ([str(path), "stroke"], "not a xacro argument"),
        ([str(tmp_path / "missing.urdf")], "missing.urdf"),
    ):
        p = subprocess.run(
            [sys.executable, "-m", "diffctl", "description", "show", *args],
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert p.returncode == 2 and p.stdout == ""
        lines = p.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("error: ") and expected in lines[0], p.stderr
