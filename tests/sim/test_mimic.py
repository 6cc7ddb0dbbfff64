"""Mimic joints in real PyBullet: a two-finger gripper whose right finger follows the left (multiplier −1, offset),
held by the physics as Gazebo's constraint holds it — free, under gravity, against an obstacle, after a reset.

The expected positions come from the mimic equation applied to the leader's own PyBullet joint state."""

from __future__ import annotations

import math

import pybullet as pb
import pytest
from sim_helpers import build, sdf_world

from diffctl.control.robot_hardware import infos_from_blocks
from diffctl.description.robot_files import parse_description
from diffctl.sim.entity import Entity
from diffctl.sim.plugins.gazebo_sim_system import GazeboSimSystem
from diffctl.sim.world import PhysicsWorld

INERTIA = '<inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/>'
MULTIPLIER, OFFSET = -1.0, 0.002


def gripper_urdf(axis: str = "0 1 0") -> str:
    """A palm fixed to the world, two prismatic fingers; the right one mimics the left (URDF <mimic>)."""
    finger = '<collision><geometry><box size="0.01 0.01 0.06"/></geometry></collision>'
    return f"""<robot name="gripper">
  <link name="world"/>
  <link name="palm"><inertial><mass value="0.5"/>{INERTIA}</inertial>
    <collision><geometry><box size="0.05 0.05 0.02"/></geometry></collision></link>
  <link name="left"><inertial><mass value="0.1"/>{INERTIA}</inertial>{finger}</link>
  <link name="right"><inertial><mass value="0.1"/>{INERTIA}</inertial>{finger}</link>
  <joint name="mount" type="fixed"><parent link="world"/><child link="palm"/><origin xyz="0 0 0.3"/></joint>
  <joint name="left_joint" type="prismatic"><parent link="palm"/><child link="left"/>
    <origin xyz="0 0.03 -0.05"/><axis xyz="{axis}"/><limit lower="-0.05" upper="0.05" effort="50" velocity="1"/></joint>
  <joint name="right_joint" type="prismatic"><parent link="palm"/><child link="right"/>
    <origin xyz="0 -0.03 -0.05"/><axis xyz="{axis}"/><limit lower="-0.05" upper="0.05" effort="50" velocity="1"/>
    <mimic joint="left_joint" multiplier="{MULTIPLIER}" offset="{OFFSET}"/></joint>
</robot>"""


def world_with(urdf: str, extra: str = "") -> tuple[PhysicsWorld, Entity]:
    pw, _ = build(sdf_world(extra))
    return pw, pw.add_model(parse_description(urdf, name="gripper"))


def positions(g: Entity) -> tuple[float, float]:
    (left, _, _), (right, _, _) = g.joint_states([g.joint("left_joint"), g.joint("right_joint")])
    return left, right


def error_m(g: Entity) -> float:
    left, right = positions(g)
    return abs(right - (MULTIPLIER * left + OFFSET))


def drive(pw: PhysicsWorld, g: Entity, velocity, steps: int) -> float:
    """Drive the leader with velocity(t); the worst mimic error seen."""
    worst = 0.0
    for i in range(steps):
        g.set_joint_velocity(g.joint("left_joint"), velocity(i * pw.step_s))
        pw.step()
        worst = max(worst, error_m(g))
    return worst


@pytest.mark.parametrize("axis", ["0 1 0", "0 0 1"], ids=["horizontal", "against-gravity"])
def test_follower_tracks_the_leader(axis: str) -> None:
    pw, g = world_with(gripper_urdf(axis))
    try:
        assert error_m(g) < 1e-9  # spawned on the relation: the offset is there from the start
        worst = drive(pw, g, lambda t: 0.05 * math.cos(2 * math.pi * t), 2000)
        assert worst < 1e-5  # 10 µm while the leader sweeps ±8 mm
        assert pb.getNumConstraints(physicsClientId=pw.client) == 1  # one gear constraint, no per-step servo
    finally:
        pw.close()


def test_a_blocked_follower_holds_the_leader_back() -> None:
    # A static block 5 mm beyond the right finger's inner face: closing the gripper drives the follower into it.
    block = """<model name="block"><static>true</static><pose>0 -0.045 0.25 0 0 0</pose><link name="l">
      <collision name="c"><geometry><box><size>0.1 0.01 0.1</size></box></geometry></collision></link></model>"""
    pw, g = world_with(gripper_urdf(), block)
    try:
        drive(pw, g, lambda t: 0.02, 2000)  # the leader's motor pushes on for 2 s
        left, right = positions(g)
        assert right == pytest.approx(-0.005, abs=1e-3)  # stopped by the block
        assert left < 0.01 and error_m(g) < 2e-3  # and so was its leader: the relation held
    finally:
        pw.close()


def test_a_static_model_with_mimic_joints_spawns() -> None:
    pw, _ = build(sdf_world(""))
    try:
        g = pw.add_model(parse_description(gripper_urdf(), name="gripper", static=True))
        assert g.joints == {} and pw.mimics["gripper"].constraints == []
        pw.reset()
    finally:
        pw.close()


def test_reset_and_remove() -> None:
    pw, g = world_with(gripper_urdf())
    try:
        drive(pw, g, lambda t: 0.03, 300)
        pw.reset()
        assert positions(g) == (0.0, pytest.approx(OFFSET))
        pw.remove("gripper")
        assert pb.getNumConstraints(physicsClientId=pw.client) == 0
    finally:
        pw.close()


def test_a_leader_in_another_body_is_followed_by_a_servo() -> None:
    """Two separate trees in one model (no joint between them): no multibody constraint reaches across, so the
    follower is servoed each step as gz_ros2_control does, with the leader's velocity fed forward."""
    pw, _ = build(sdf_world(""))
    body = """<link name="{p}base"><pose>{x} 0 0.3 0 0 0</pose><inertial><mass>1</mass></inertial></link>
      <link name="{p}slider"><pose>{x} 0 0.2 0 0 0</pose><inertial><mass>0.1</mass></inertial></link>
      <joint name="{p}pin" type="fixed"><parent>world</parent><child>{p}base</child></joint>
      <joint name="{p}joint" type="prismatic"><parent>{p}base</parent><child>{p}slider</child>
        <axis><xyz>1 0 0</xyz><limit><lower>-1</lower><upper>1</upper><effort>50</effort></limit>{m}</axis></joint>"""
    mimic = "<mimic joint='a_joint'><multiplier>0.5</multiplier><offset>0.01</offset></mimic>"
    sdf = f"""<sdf version="1.11"><model name="pair">{body.format(p="a_", x=0, m="")}
      {body.format(p="b_", x=1, m=mimic)}</model></sdf>"""
    try:
        pair = pw.add_model(parse_description(sdf))
        lead, follow = pair.joint("a_joint"), pair.joint("b_joint")
        assert lead.body != follow.body
        worst = 0.0
        for i in range(1500):
            pair.set_joint_velocity(lead, 0.1 * math.sin(2 * math.pi * i * pw.step_s))
            pw.step()
            (ql, _, _), (qf, _, _) = pair.joint_states([lead, follow])
            worst = max(worst, abs(qf - (0.5 * ql + 0.01)))
        assert worst < 1e-4 and abs(ql) > 0.005
    finally:
        pw.close()


def test_gz_ros2_control_drives_the_leader_and_leaves_the_follower_to_the_physics() -> None:
    """ros2_control lists both fingers (the follower with state interfaces only, as gripper descriptions do):
    the idle follower is not held at zero, so commanding the leader's position closes both fingers."""
    block = """<ros2_control name="GripperSystem" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="left_joint"><command_interface name="position"/><state_interface name="position"/></joint>
    <joint name="right_joint"><state_interface name="position"/></joint>
  </ros2_control>
</robot>"""
    pw, g = world_with(gripper_urdf().replace("</robot>", block))
    try:
        info = infos_from_blocks(g.model.ros2_control, "gripper.urdf")[0]
        hw = GazeboSimSystem().bind(g, hold_joints=True, position_proportional_gain=0.1)
        hw.update_rate = 100
        hw.on_init(info)
        hw.export_state_interfaces()
        hw.export_command_interfaces()
        hw.perform_command_mode_switch(["left_joint/position"], [])
        hw.commands["left_joint/position"].value = 0.03
        for i in range(2000):
            if i % 10 == 0:
                hw.write(0, 0.01)
            hw.step()
            pw.step()
        hw.read(0, 0.01)
        assert hw.states["left_joint/position"].value == pytest.approx(0.03, abs=1e-3)
        assert hw.states["right_joint/position"].value == pytest.approx(MULTIPLIER * 0.03 + OFFSET, abs=1e-3)
        assert error_m(g) < 1e-5
    finally:
        pw.close()
