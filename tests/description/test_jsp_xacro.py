"""`diffctl joint-state-publisher FILE` expands a xacro file as the xacro tool does, and reports a bad one in one line.

The joints expected are read from what the real `xacro` package makes of the same file."""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any

import xacro
from lxml import etree

from tests.conftest import Procs
from tests.probe import Probe
from tests.waiting import wait_for

GRIPPER_XACRO = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="gripper">
  <xacro:property name="stroke" value="0.04"/>
  <xacro:macro name="finger" params="side sign">
    <link name="${side}_finger"/>
    <joint name="${side}_finger_joint" type="prismatic">
      <parent link="palm"/><child link="${side}_finger"/>
      <origin xyz="0 ${sign * 0.05} 0"/><axis xyz="0 ${sign} 0"/>
      <limit lower="${-stroke}" upper="${stroke / 2}" effort="10" velocity="0.1"/>
    </joint>
  </xacro:macro>
  <link name="palm"/>
  <link name="wrist"/>
  <joint name="wrist_joint" type="continuous"><parent link="wrist"/><child link="palm"/></joint>
  <xacro:finger side="left" sign="1"/>
  <xacro:finger side="right" sign="-1"/>
</robot>
"""


def moving_joints(urdf_text: str) -> list[str]:
    root = etree.fromstring(urdf_text.encode())
    return [j.get("name") for j in root.iter("joint") if j.get("type") != "fixed"]


def test_a_xacro_file_is_expanded(router: str, procs: Procs, tmp_path: Path) -> None:
    path = tmp_path / "gripper.urdf.xacro"
    path.write_text(GRIPPER_XACRO)
    expected = moving_joints(xacro.process_file(str(path)).toprettyxml())
    assert len(expected) == 3  # the macro really ran

    jsp = procs.diffctl("joint-state-publisher", str(path), "--ros-args", "-p", "rate:=50")
    node = Probe("jsp_xacro_probe")
    try:
        got: list[Any] = []
        lock = threading.Lock()

        def keep(msg: Any) -> None:
            with lock:
                got.append(msg)

        node.create_subscription("/joint_states", "sensor_msgs/msg/JointState", keep)
        assert wait_for(lambda: len(got) >= 2, timeout_s=60), (procs.stop(jsp), jsp.stdout.read())
        with lock:
            last = got[-1]
        assert sorted(last.name) == sorted(expected)
        positions = dict(zip(last.name, last.position, strict=True))
        for side in ("left", "right"):
            assert -0.04 <= positions[f"{side}_finger_joint"] <= 0.02  # the ${…} limits were evaluated
    finally:
        node.close()
    assert procs.stop(jsp) == 0


def test_a_broken_xacro_file_is_one_line_and_exit_2(procs: Procs, tmp_path: Path) -> None:
    path = tmp_path / "broken.urdf.xacro"
    path.write_text(GRIPPER_XACRO.replace('sign="-1"', ""))  # a macro call missing a parameter
    p = procs.diffctl("joint-state-publisher", str(path))
    out = p.stdout.read()
    assert p.wait(60) == 2
    lines = out.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and str(path) in lines[0], out
