"""Gazebo's joint and velocity systems on a real PyBullet model: each reaches its target as gz-sim 8's does.

JointPositionController (PID on the position error into an effort, or a velocity that closes the error in one
step), JointController (velocity, or a PID on the velocity error), ApplyJointForce (a held effort),
JointTrajectoryController (points taken in turn by time_from_start, progress published) and VelocityControl
(a model moved at a body-frame twist); default topics as gz-sim names them.
"""

from __future__ import annotations

import math
import threading

import pytest
from sim_helpers import ground, sdf_world

from diffctl.description.pose import rpy_from_quat
from diffctl.sim.plugins.apply_joint_force import ApplyJointForce
from diffctl.sim.plugins.joint_controller import JointController
from diffctl.sim.plugins.joint_position_controller import JointPositionController
from diffctl.sim.plugins.joint_trajectory_controller import JointTrajectoryController
from diffctl.sim.plugins.velocity_control import VelocityControl
from diffctl.sim.runner import Simulation

IZZ = 0.02  # each arm link turns about its own centre of mass (vertical axis, no gravity torque)


def advance(sim: Simulation, steps: int) -> None:
    done = threading.Event()
    sim.stepper.set_paused(True)
    sim.stepper.step_n(steps, done.set)
    sim.run(done)


def arm(plugins: str) -> str:
    links, joints = ["<link name='base'><inertial><mass>5</mass></inertial></link>"], []
    for i in range(1, 7):
        links.append(
            f"<link name='l{i}'><pose>{i * 0.3} 0 0.5 0 0 0</pose><inertial><mass>1</mass><inertia><ixx>{IZZ}</ixx>"
            f"<iyy>{IZZ}</iyy><izz>{IZZ}</izz></inertia></inertial><visual name='v'><geometry><box><size>0.2 0.05 "
            "0.05</size></box></geometry></visual></link>"
        )
        joints.append(
            f"<joint name='j{i}' type='continuous'><parent>base</parent><child>l{i}</child><axis><xyz>0 0 1</xyz>"
            "</axis></joint>"
        )
    fixed = "<joint name='anchor' type='fixed'><parent>world</parent><child>base</child></joint>"
    return f"<model name='arm'>{''.join(links)}{''.join(joints)}{fixed}{plugins}</model>"


def plugin(kind: str, cls: str, body: str) -> str:
    return f'<plugin filename="gz-sim-{kind}-system" name="gz::sim::systems::{cls}">{body}</plugin>'


def test_joint_controllers_reach_their_targets() -> None:
    plugins = (
        plugin("joint-position-controller", "JointPositionController", "<joint_name>j1</joint_name><d_gain>.3</d_gain>")
        + plugin(
            "joint-position-controller",
            "JointPositionController",
            "<joint_name>j2</joint_name><use_velocity_commands>true</use_velocity_commands><topic>j2_pos</topic>",
        )
        + plugin("joint-controller", "JointController", "<joint_name>j3</joint_name>")
        + plugin(
            "joint-controller",
            "JointController",
            "<joint_name>j4</joint_name><use_force_commands>true</use_force_commands><p_gain>0.5</p_gain>"
            "<sub_topic>speed</sub_topic>",
        )
        + plugin("apply-joint-force", "ApplyJointForce", "<joint_name>j5</joint_name>")
    )
    sim = Simulation(sdf_world(arm(plugins)), rtf=0.0)
    try:
        systems = sim.models["arm"].plugins
        jpc, jpc_vel = (p for p in systems if isinstance(p, JointPositionController))
        jc, jc_force = (p for p in systems if isinstance(p, JointController))
        (force,) = (p for p in systems if isinstance(p, ApplyJointForce))
        assert jpc.topic == "/model/arm/joint/j1/0/cmd_pos" and jpc_vel.topic == "/j2_pos"
        assert jc.topic == "/model/arm/joint/j3/cmd_vel" and jc_force.topic == "/model/arm/speed"
        assert force.topic == "/model/arm/joint/j5/cmd_force"
        entity = sim.models["arm"].entity
        joints = [entity.joint(f"j{i}") for i in range(1, 7)]
        jpc.command(0.8)
        jpc_vel.command(-0.5)
        jc.on_double({"data": 1.5})
        jc_force.on_double({"data": -2.0})
        force.on_force({"data": 0.01})
        advance(sim, 4000)
        state = entity.joint_states(joints)
        assert state[0][0] == pytest.approx(0.8, abs=0.01)  # the default PID (p 1, i 0.1) with more damping
        assert state[1][0] == pytest.approx(-0.5, abs=1e-3)  # velocity commands close the error in a step
        assert state[2][1] == pytest.approx(1.5, abs=1e-3)
        assert state[3][1] == pytest.approx(-2.0, abs=0.01)  # the velocity PID's effort balances nothing
        # a held effort τ on a free joint: ω = τ t / I after t = 4 s
        assert state[4][1] == pytest.approx(0.01 * 4.0 / IZZ, rel=0.02)
        assert state[5][0] == pytest.approx(0.0, abs=1e-6)  # j6: no system
    finally:
        sim.close()


def test_joint_trajectory_controller_follows_points_in_time() -> None:
    body = (
        "<joint_name>j1</joint_name><joint_name>j2</joint_name>"
        "<position_p_gain>4</position_p_gain><position_p_gain>4</position_p_gain>"
        "<position_d_gain>0.6</position_d_gain><position_d_gain>0.6</position_d_gain>"
        "<initial_position>0.2</initial_position>"
    )
    sim = Simulation(sdf_world(arm(plugin("joint-trajectory-controller", "JointTrajectoryController", body))), rtf=0)
    try:
        (jtc,) = (p for p in sim.models["arm"].plugins if isinstance(p, JointTrajectoryController))
        assert jtc.topic == "/model/arm/joint_trajectory"
        assert jtc.progress_topic == "/model/arm/joint_trajectory_progress"
        entity = sim.models["arm"].entity
        j1, j2 = entity.joint("j1"), entity.joint("j2")
        advance(sim, 3000)  # initial_position holds j1 at 0.2, j2 at 0
        assert [s[0] for s in entity.joint_states([j1, j2])] == pytest.approx([0.2, 0.0], abs=0.01)
        jtc.on_trajectory(
            {
                "joint_names": ["j2", "j1"],
                "points": [
                    {"positions": [0.5, -0.3], "time_from_start": {"sec": 1, "nsec": 0}},
                    {"positions": [1.0, -0.6], "time_from_start": {"sec": 2, "nsec": 500_000_000}},
                ],
            }
        )
        advance(sim, 2000)  # 2 s: the first point's time has passed, the second is the target now
        assert jtc.point_index == 1 and jtc.status == "reached"
        advance(sim, 4000)
        assert [s[0] for s in entity.joint_states([j1, j2])] == pytest.approx([-0.6, 1.0], abs=0.01)
    finally:
        sim.close()


def test_velocity_control_moves_a_model_at_its_body_twist() -> None:
    box = (
        "<model name='crate'><pose>0 0 0.1 0 0 0</pose><link name='body'><inertial><mass>2</mass></inertial>"
        "<collision name='c'><geometry><box><size>0.4 0.4 0.2</size></box></geometry>"
        "<surface><friction><ode><mu>0</mu></ode></friction></surface></collision></link>"  # (no drag on the ground)
        + plugin("velocity-control", "VelocityControl", "")
        + "</model>"
    )
    sim = Simulation(sdf_world(ground() + box), rtf=0.0)
    try:
        (vc,) = (p for p in sim.models["crate"].plugins if isinstance(p, VelocityControl))
        assert vc.topic == "/model/crate/cmd_vel"
        entity = sim.models["crate"].entity
        vc.on_model_twist({"linear": {"x": 0.5}, "angular": {"z": 0.5}})
        advance(sim, 2000)
        p = entity.pose()
        heading = rpy_from_quat(p.quat)[2]
        assert heading == pytest.approx(1.0, abs=0.01)  # 0.5 rad/s for 2 s (less the step before it starts)
        # a 1 m radius circle from the origin, heading along +x: (sin θ, 1 − cos θ)
        assert p.xyz[:2] == pytest.approx((math.sin(heading), 1 - math.cos(heading)), abs=0.01)
    finally:
        sim.close()
