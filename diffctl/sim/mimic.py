"""Mimic joints (SDF 1.11 `<axis><mimic>`, URDF `<mimic>`): follower = multiplier · leader + offset, held by physics.

Gazebo Harmonic enforces `<mimic>` in the physics engine as a constraint: gz-physics' bullet-featherstone
backend makes it a `btMultiBodyGearConstraint` (gear ratio −multiplier, position target offset), so a blocked
follower holds its leader back as a real linkage would. PyBullet exposes the same constraint as JOINT_GEAR, used
here whenever both joints are in one PyBullet multibody (always, for a model whose links form one tree).

Measured on a two-finger gripper (1 ms steps, leader driven sinusoidally at up to 0.05 m/s; follower blocked by
a static box while the leader pushes on):
- JOINT_GEAR, ERP 1.0: 0.0016 mm free, 0.5 mm blocked (the leader stops); ERP 0.3 (gz-physics' value): 0.005 mm
  free, 1.6 mm blocked; no Python work per step;
- gz_ros2_control's servo (velocity −(follower − multiplier · leader − offset) · rate each step): 0.05 mm free
  (one step of lag), 0.0003 mm with the leader's velocity fed forward; a blocked follower breaks the relation
  by 35 mm (the leader runs on: the follower is only a motor), and three PyBullet calls every step.
So the gear constraint at ERP 1.0 is the default; the servo (with feed-forward) remains for a leader in another
PyBullet body (a model made of several separate trees), where no multibody constraint can reach.
"""

from __future__ import annotations

from dataclasses import dataclass

import pybullet as pb

from diffctl.description.model import Model
from diffctl.errors import DescriptionError
from diffctl.sim.entity import Entity, JointHandle

# Error reduction per step: 1.0 corrects the whole position error in one step (measured stable, see above).
GEAR_ERP = 1.0
# A linkage, not a motor: effectively unbounded, as gz-physics' own (max applied impulse 1e8).
GEAR_MAX_FORCE = 1e8


@dataclass(frozen=True)
class MimicSpec:
    """follower position = multiplier · leader position + offset (SDF's reference already folded in)."""

    follower: str
    leader: str
    multiplier: float
    offset: float


def mimic_specs(model: Model) -> list[MimicSpec]:
    """The model's mimic relations, leaders before their followers (a chain settles in one pass at spawn)."""
    specs = {j.name: MimicSpec(j.name, *j.mimic) for j in model.joints if j.mimic is not None}
    ordered: list[MimicSpec] = []
    placed: set[str] = set()

    def place(name: str) -> None:
        if name in placed or name not in specs:
            return
        placed.add(name)  # the loader refused loops, so marking first cannot hide one
        place(specs[name].leader)
        ordered.append(specs[name])

    for name in specs:
        place(name)
    return ordered


def follower_position(spec: MimicSpec, leader_position: float) -> float:
    return spec.multiplier * leader_position + spec.offset


def servo_velocity(spec: MimicSpec, leader: tuple[float, float], follower_position_now: float, step_s: float) -> float:
    """gz_ros2_control's mimic servo with the leader's velocity fed forward: cancels the error in one step."""
    leader_position, leader_velocity = leader
    error = follower_position_now - follower_position(spec, leader_position)
    return spec.multiplier * leader_velocity - error / step_s


class Mimics:
    """The mimic relations of one spawned entity: gear constraints, and servos run before each step."""

    def __init__(self, entity: Entity, step_s: float) -> None:
        self.entity = entity
        self.step_s = step_s
        self.constraints: list[int] = []
        self.servos: list[tuple[MimicSpec, JointHandle, JointHandle]] = []
        cid = entity.client
        # A static model has no moving joints: nothing to relate.
        for spec in [] if entity.model.static else mimic_specs(entity.model):
            follower, leader = self._handle(spec.follower), self._handle(spec.leader)
            # Start on the relation (joints spawn at zero): no first-step jolt to correct an offset.
            lead_pos = pb.getJointState(leader.body, leader.index, physicsClientId=cid)[0]
            pb.resetJointState(
                follower.body, follower.index, follower_position(spec, lead_pos), 0.0, physicsClientId=cid
            )
            if follower.body == leader.body:
                self.constraints.append(self._gear(spec, follower, leader))
            else:
                self.servos.append((spec, follower, leader))

    def _handle(self, name: str) -> JointHandle:
        handle = self.entity.joints.get(name)
        if handle is None or handle.joint.type == "ball":
            raise DescriptionError(
                f"mimic joint {name!r} of model {self.entity.name!r} is not a single-axis moving joint",
                source=self.entity.model.source or None,
                field=f"joint {name}",
            )
        return handle

    def _gear(self, spec: MimicSpec, follower: JointHandle, leader: JointHandle) -> int:
        cid = self.entity.client
        # btMultiBodyGearConstraint keeps q_A + ratio · q_B = target, A the follower and B the leader.
        c = pb.createConstraint(
            follower.body,
            follower.index,
            leader.body,
            leader.index,
            pb.JOINT_GEAR,
            [0.0, 0.0, 1.0],
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
            physicsClientId=cid,
        )
        pb.changeConstraint(
            c,
            gearRatio=-spec.multiplier,
            relativePositionTarget=spec.offset,
            erp=GEAR_ERP,
            maxForce=GEAR_MAX_FORCE,
            physicsClientId=cid,
        )
        return c

    def before_step(self) -> None:
        """Drive every servoed follower onto its relation for the coming step."""
        cid = self.entity.client
        for spec, follower, leader in self.servos:
            lead = pb.getJointState(leader.body, leader.index, physicsClientId=cid)[:2]
            now = pb.getJointState(follower.body, follower.index, physicsClientId=cid)[0]
            velocity = servo_velocity(spec, (lead[0], lead[1]), now, self.step_s)
            self.entity.set_joint_velocity(follower, velocity)

    def reset(self) -> None:
        """After the entity's reset (joints at zero): followers back onto their relations."""
        cid = self.entity.client
        for spec in [] if self.entity.model.static else mimic_specs(self.entity.model):
            follower, leader = self.entity.joints[spec.follower], self.entity.joints[spec.leader]
            lead_pos = pb.getJointState(leader.body, leader.index, physicsClientId=cid)[0]
            pb.resetJointState(
                follower.body, follower.index, follower_position(spec, lead_pos), 0.0, physicsClientId=cid
            )

    def close(self) -> None:
        for c in self.constraints:
            try:
                pb.removeConstraint(c, physicsClientId=self.entity.client)
            except pb.error:
                pass  # already gone with its body
        self.constraints.clear()
