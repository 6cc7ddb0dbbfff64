"""A spawned model in the physics world: where its SDF links are, its joints, and commands to them.

Reads go straight to PyBullet for only what is asked (no per-step polling of joints nobody reads);
velocity commands set PyBullet's joint motors once and persist until the next command.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import pybullet as pb

from diffctl.description.model import Joint, Model
from diffctl.description.pose import Pose, Vec3
from diffctl.errors import DescriptionError, suggest
from diffctl.sim.body_plan import BodyPlan, ModelPlan

# A joint without an <effort> limit is driven as Gazebo's velocity command would (nearly ideally).
DEFAULT_MAX_EFFORT = 1000.0
# Without a <velocity> limit, commands are still capped: absurd values never reach the physics.
DEFAULT_MAX_SPEED = 1000.0
# A joint commanded to 0 rad/s is held where it came to rest. PyBullet's velocity motor alone leaves a small
# constant residual velocity (its iterative solve never quite meets the contacts), which integrates into
# creep: an idle car with wheels "held" this way crept 2.5 mm and 0.011 rad a minute. A weak position term
# (rhs = gain * error / step: 1 rad/s per rad of error at 1 ms) bounds that error instead of integrating it,
# as Gazebo's exact velocity servo does, and is too weak to be felt while settling.
HOLD_POSITION_GAIN = 0.001
# A held joint is anchored once it has (nearly) stopped, so a stop from speed does not spring back.
HOLD_SETTLED_RAD_S = 1e-3


@dataclass(frozen=True)
class JointHandle:
    name: str
    body: int
    index: int
    joint: Joint
    max_effort: float
    max_velocity: float


@dataclass(frozen=True)
class Belt:
    """The belt under a model's tracks (body_plan's _split_belts): the PyBullet link they are fixed to
    (`carrier`), the belt's joints along the tracks' x and y and about their z (the axes in the carrier's frame,
    through its origin), the PyBullet links holding the tracks' collisions, and each track's centre there."""

    body: int
    carrier: int
    joints: tuple[int, int, int]
    axes: tuple[Vec3, Vec3, Vec3]
    links: frozenset[int]
    centres: dict[str, Vec3]


def _belt(body: int, plan: BodyPlan, index: int) -> Belt:
    links = plan.links  # (PyBullet index i is links[i + 1])
    turn = links[index + 1]
    slide_y = turn.parent
    slide_x = links[slide_y + 1].parent
    carrier = links[slide_x + 1].parent
    held = {index}
    for i, lp in enumerate(links[1:]):  # the tracks' other surfaces and shapes, fixed to the belt
        if lp.joint is None and lp.parent in held:
            held.add(i)
    axes = (links[slide_x + 1].axis, links[slide_y + 1].axis, turn.axis)
    return Belt(body, carrier, (slide_x, slide_y, index), axes, frozenset(held), dict(turn.belt))


class Entity:
    def __init__(self, client: int, model: Model, plan: ModelPlan, bodies: tuple[int, ...]) -> None:
        self.client = client
        self.model = model
        self.name = model.name
        self.plan = plan
        self.bodies = bodies
        self.joints: dict[str, JointHandle] = {}
        for j in model.joints:
            if j.name in plan.joints:
                body_no, index = plan.joints[j.name]
                lim = j.limits
                effort = lim.effort if math.isfinite(lim.effort) and lim.effort > 0 else DEFAULT_MAX_EFFORT
                vmax = lim.velocity if math.isfinite(lim.velocity) and lim.velocity > 0 else DEFAULT_MAX_SPEED
                self.joints[j.name] = JointHandle(j.name, bodies[body_no], index, j, effort, vmax)
        # Joints commanded to 0: name → the position they are held at, or None until they have stopped.
        self._held: dict[str, float | None] = {}
        self.settling = False  # some held joint still awaits its anchor (PhysicsWorld.step calls settle_holds)
        # Non-zero velocity or effort commands so far (gz's LinearBatteryPlugin starts draining on the first).
        self.motion_commands = 0
        # Efforts systems added for the next step, summed as gz-sim sums JointForceCmd (applied before the step).
        self.pending_efforts: dict[str, tuple[JointHandle, float]] = {}
        # Tracks' belts (TrackController): SDF track link → the belt it rides on (shared by tracks fixed together).
        self.belts: dict[str, Belt] = {}
        for b, bp in enumerate(plan.bodies):
            for index, lp in enumerate(bp.links, start=-1):
                if lp.belt:
                    belt = _belt(bodies[b], bp, index)
                    self.belts.update((name, belt) for name in belt.centres)
        # Spawn state, for world reset: base link frames and (zero) joint positions.
        self._initial = [(b, plan.bodies[i].links[0]) for i, b in enumerate(bodies)]

    # --- poses ---------------------------------------------------------------------------------------

    def link_frame(self, name: str) -> tuple[int, int, Pose]:
        """(PyBullet body, link index, offset of the SDF link in that PyBullet link's frame)."""
        ref = self.plan.links[name]
        return self.bodies[ref.body], ref.pb_link, ref.offset

    def pb_link_pose(self, body: int, index: int) -> Pose:
        """World pose of a PyBullet link frame (the base's too, which PyBullet reports at its centre of mass)."""
        if index < 0:
            pos, orn = pb.getBasePositionAndOrientation(body, physicsClientId=self.client)
            inertial = self.inertial_frame(body, -1)
            return Pose(tuple(pos), tuple(orn)).compose(inertial.inverse())
        st = pb.getLinkState(body, index, computeForwardKinematics=1, physicsClientId=self.client)
        return Pose(tuple(st[4]), tuple(st[5]))

    def link_pose(self, name: str) -> Pose:
        body, index, offset = self.link_frame(name)
        return self.pb_link_pose(body, index).compose(offset)

    def pose(self) -> Pose:
        """The model frame in the world (Gazebo's model pose), following the canonical link."""
        canonical = self.model.canonical_link or self.model.root_link()
        link0 = self.model.link(canonical)
        link_in_model = self.model.pose_world.inverse().compose(link0.pose_world)
        return self.link_pose(canonical).compose(link_in_model.inverse())

    def link_velocity(self, name: str, point_world: Vec3 | None = None) -> tuple[Vec3, Vec3]:
        """(linear velocity of `point_world` (default: the link origin) on the link, angular velocity), world."""
        body, index, offset = self.link_frame(name)
        if index < 0:
            lin, ang = pb.getBaseVelocity(body, physicsClientId=self.client)
            com, _ = pb.getBasePositionAndOrientation(body, physicsClientId=self.client)
            frame = None
        else:
            st = pb.getLinkState(
                body, index, computeLinkVelocity=1, computeForwardKinematics=1, physicsClientId=self.client
            )
            lin, ang, com = st[6], st[7], st[0]
            frame = Pose(tuple(st[4]), tuple(st[5]))
        if point_world is None:
            if frame is None:
                frame = self.pb_link_pose(body, index)
            point_world = frame.compose(offset).xyz
        r = (point_world[0] - com[0], point_world[1] - com[1], point_world[2] - com[2])
        v = (
            lin[0] + ang[1] * r[2] - ang[2] * r[1],
            lin[1] + ang[2] * r[0] - ang[0] * r[2],
            lin[2] + ang[0] * r[1] - ang[1] * r[0],
        )
        return v, (ang[0], ang[1], ang[2])

    def com_state(self, body: int, index: int) -> tuple[Pose, Vec3, Vec3]:
        """(centre-of-mass frame in the world, its linear velocity, angular velocity) of a PyBullet link."""
        cid = self.client
        if index < 0:
            pos, orn = pb.getBasePositionAndOrientation(body, physicsClientId=cid)
            lin, ang = pb.getBaseVelocity(body, physicsClientId=cid)
        else:
            st = pb.getLinkState(body, index, computeLinkVelocity=1, computeForwardKinematics=1, physicsClientId=cid)
            pos, orn, lin, ang = st[0], st[1], st[6], st[7]
        return Pose(tuple(pos), tuple(orn)), tuple(lin), tuple(ang)

    def inertial_frame(self, body: int, index: int) -> Pose:
        """The centre-of-mass frame of a PyBullet link in its link frame (PyBullet reports and casts in it)."""
        return self.plan.bodies[self.bodies.index(body)].links[index + 1].inertial_frame

    # --- joints --------------------------------------------------------------------------------------

    def joint(self, name: str) -> JointHandle:
        try:
            return self.joints[name]
        except KeyError:
            raise DescriptionError(
                f"model {self.name!r} has no moving joint {name!r}{suggest(name, self.joints)}",
                hint=f"moving joints: {', '.join(self.joints) or 'none'}",
            ) from None

    def joint_states(self, handles: list[JointHandle]) -> list[tuple[float, float, float]]:
        """(position, velocity, applied motor effort) of each joint."""
        out = []
        for h in handles:
            pos, vel, _forces, torque = pb.getJointState(h.body, h.index, physicsClientId=self.client)
            out.append((pos, vel, torque))
        return out

    def set_joint_velocity(self, h: JointHandle, velocity: float) -> None:
        """Drive a joint at `velocity` (clamped to its limit) until told otherwise; 0 holds it."""
        v = max(-h.max_velocity, min(h.max_velocity, velocity)) if math.isfinite(velocity) else 0.0
        if v == 0.0:
            if h.name in self._held:
                return  # already held (a controller repeats its zero every cycle): keep the anchor
            self._held[h.name] = None
            self.settling = True
        else:
            self.motion_commands += 1
            self._held.pop(h.name, None)
        pb.setJointMotorControl2(
            h.body, h.index, pb.VELOCITY_CONTROL, targetVelocity=v, force=h.max_effort, physicsClientId=self.client
        )

    def set_joint_effort(self, h: JointHandle, effort: float) -> None:
        """Apply `effort` for the next step only (PyBullet clears applied torques after each step)."""
        e = max(-h.max_effort, min(h.max_effort, effort)) if math.isfinite(effort) else 0.0
        self._held.pop(h.name, None)
        if e != 0.0:
            self.motion_commands += 1
        pb.setJointMotorControl2(h.body, h.index, pb.VELOCITY_CONTROL, force=0.0, physicsClientId=self.client)
        pb.setJointMotorControl2(h.body, h.index, pb.TORQUE_CONTROL, force=e, physicsClientId=self.client)

    def add_joint_effort(self, h: JointHandle, effort: float) -> None:
        """Add `effort` to what the joint gets in the next step (Gazebo systems' JointForceCmd)."""
        if math.isfinite(effort):
            _, total = self.pending_efforts.get(h.name, (h, 0.0))
            self.pending_efforts[h.name] = (h, total + effort)

    def apply_efforts(self) -> None:
        """Hand the summed efforts to the physics for the coming step (PhysicsWorld.step calls it)."""
        for h, effort in self.pending_efforts.values():
            self.set_joint_effort(h, effort)
        self.pending_efforts.clear()

    def reset_joint(self, h: JointHandle, *, position: float | None = None, velocity: float | None = None) -> None:
        """Set a joint's position and/or velocity outright (gz's JointPositionReset / JointVelocityReset)."""
        pos, vel, _f, _t = pb.getJointState(h.body, h.index, physicsClientId=self.client)
        if h.name in self._held:
            self._unanchor(h)
        pb.resetJointState(
            h.body,
            h.index,
            pos if position is None else position,
            vel if velocity is None else velocity,
            physicsClientId=self.client,
        )

    def release_joint(self, h: JointHandle) -> None:
        """Back to a free joint with only its SDF friction."""
        self._held.pop(h.name, None)
        pb.setJointMotorControl2(
            h.body,
            h.index,
            pb.VELOCITY_CONTROL,
            targetVelocity=0.0,
            force=max(0.0, h.joint.dynamics.friction),
            physicsClientId=self.client,
        )

    def settle_holds(self) -> None:
        """Anchor each held joint that has stopped at the position it stopped at (called before a step)."""
        cid = self.client
        waiting = False
        for name, anchor in self._held.items():
            if anchor is not None:
                continue
            h = self.joints[name]
            pos, vel, _f, _t = pb.getJointState(h.body, h.index, physicsClientId=cid)
            if abs(vel) > HOLD_SETTLED_RAD_S:
                waiting = True
                continue
            self._held[name] = pos
            pb.setJointMotorControl2(
                h.body,
                h.index,
                pb.POSITION_CONTROL,
                targetPosition=pos,
                targetVelocity=0.0,
                positionGain=HOLD_POSITION_GAIN,
                velocityGain=1.0,
                force=h.max_effort,
                physicsClientId=cid,
            )
        self.settling = waiting

    def _unanchor(self, h: JointHandle) -> None:
        # Moved outright: hold again by velocity until it has stopped, then anchor anew.
        self._held[h.name] = None
        self.settling = True
        pb.setJointMotorControl2(
            h.body, h.index, pb.VELOCITY_CONTROL, targetVelocity=0.0, force=h.max_effort, physicsClientId=self.client
        )

    # --- reset ---------------------------------------------------------------------------------------

    def reset(self) -> None:
        """Back to the spawn pose, at rest, joints at zero."""
        cid = self.client
        for body, base in self._initial:
            com = base.frame_world.compose(base.inertial_frame)
            pb.resetBasePositionAndOrientation(body, com.xyz, com.quat, physicsClientId=cid)
            pb.resetBaseVelocity(body, [0, 0, 0], [0, 0, 0], physicsClientId=cid)
        for h in self.joints.values():
            if h.joint.type == "ball":
                pb.resetJointStateMultiDof(h.body, h.index, [0, 0, 0, 1], [0, 0, 0], physicsClientId=cid)
            else:
                pb.resetJointState(h.body, h.index, 0.0, 0.0, physicsClientId=cid)
            if h.name in self._held:
                self._unanchor(h)
        for body, plan in zip(self.bodies, self.plan.bodies, strict=True):
            for index, lp in enumerate(plan.links, start=-1):
                if lp.gear is not None:  # a mecanum roller goes back to zero with its wheel
                    pb.resetJointState(body, index, 0.0, 0.0, physicsClientId=cid)
