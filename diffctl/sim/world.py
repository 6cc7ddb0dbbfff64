"""The PyBullet physics world: one physics client per sim, fixed time step, bodies built from SDF models.

DIRECT mode (headless, the default) or GUI mode (PyBullet's OpenGL window, Gazebo's GUI counterpart).
Determinism: real-time simulation is off, the step is fixed to the world's `max_step_size`, overlapping
pairs are sorted (`deterministicOverlappingPairs`), and nothing depends on wall time, so the same world,
the same commands at the same steps and the same seed give bit-identical trajectories.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import pybullet as pb

from diffctl.description.model import Box, Capsule, Cylinder, Mesh, Model, Physics, Plane, Sphere
from diffctl.description.pose import Pose, Vec3
from diffctl.errors import DescriptionError, RuntimeFailure
from diffctl.sim import self_collision
from diffctl.sim.body_plan import BodyPlan, LinkPlan, ShapeSpec, plan_model
from diffctl.sim.entity import Entity
from diffctl.sim.flat_planes import FlatPlane
from diffctl.sim.link_gravity import GravityOff
from diffctl.sim.mimic import GEAR_ERP, GEAR_MAX_FORCE, Mimics

# PyBullet defaults to 50. 10 gave the same drive trajectories (to 0.1 mm over 6 s) for a third of the cost,
# but left held wheels slipping: a car standing on held wheels turned 0.002 rad a minute at 10, 0.00015 at 20.
# With one fresh contact per wheel (wheel_contact.py), robots on held wheels at yaw 0.7 slid a minute at
# 20 / 30 / 40 / 50 iterations: TurtleBot-like 1.59 / 0.51 / 0.15 / 0.05 mm, the tutorial car 0.53 / 0.45 /
# 0.26 / 0.15 mm (free wheels converge before 30; tests/sim/test_idle_creep.py). Stepping the driving car costs
# +13 % at 30, +28 % at 40, +45 % at 50 over 20 (bench.sim, CPU time). At rest the solve exits early anyway.
SOLVER_ITERATIONS = 30
# Bullet stops iterating once the solve's residual is under 1e-7 (its default). At rest that leaves small
# velocities every step which integrate: on free wheels next to a frictionless caster the residual fed back
# through the contact points and an idle car rolled away (0.85 m in 20 s); everywhere else it crept ~0.1 mm
# and 0.003 rad a minute. Converging fully costs nothing measurable while driving (the residual is never
# that small then). (0 would read as "unset" and keep the default.)
SOLVER_RESIDUAL_THRESHOLD = 1e-12
# A visual plane is drawn as a thin box just under the collision plane.
PLANE_VISUAL_THICKNESS_M = 0.002

_JOINT_TYPES = {
    "revolute": pb.JOINT_REVOLUTE,
    "continuous": pb.JOINT_REVOLUTE,
    "prismatic": pb.JOINT_PRISMATIC,
    "fixed": pb.JOINT_FIXED,
    "ball": pb.JOINT_SPHERICAL,
}


# A headless PyBullet client connected ahead of need (the fork server's, see `reserve_client`): connecting
# costs 10-13 ms, on the simulator's path to its first spawn.
_spare_client: int | None = None


def reserve_client() -> None:
    """Connect one headless client now for the first PhysicsWorld of this process (or of its forks) to take."""
    global _spare_client
    if _spare_client is None:
        _spare_client = pb.connect(pb.DIRECT)


def _connect(gui: bool) -> int:
    global _spare_client
    spare, _spare_client = _spare_client, None
    if spare is not None:
        if not gui and pb.isConnected(physicsClientId=spare):
            return spare
        pb.disconnect(physicsClientId=spare)
    return pb.connect(pb.GUI if gui else pb.DIRECT)


class PhysicsWorld:
    """A PyBullet client with the world's physics settings and the entities spawned into it."""

    def __init__(self, physics: Physics, *, gui: bool = False) -> None:
        step = physics.max_step_size_s
        if not (math.isfinite(step) and 1e-5 <= step <= 0.1):
            raise DescriptionError(
                f"<max_step_size> {step!r} is out of range", field="physics", hint="valid: 1e-05 .. 0.1 s"
            )
        self.physics = physics
        self.step_s = step
        self.step_ns = round(step * 1e9)
        self.gui = gui
        self.client = _connect(gui)
        if self.client < 0:
            raise RuntimeFailure("cannot open the PyBullet window (is there a display? try without --gui)")
        cid = self.client
        if gui:
            pb.configureDebugVisualizer(pb.COV_ENABLE_GUI, 0, physicsClientId=cid)
        pb.setRealTimeSimulation(0, physicsClientId=cid)
        pb.setTimeStep(step, physicsClientId=cid)
        pb.setPhysicsEngineParameter(
            numSubSteps=0,
            numSolverIterations=SOLVER_ITERATIONS,
            solverResidualThreshold=SOLVER_RESIDUAL_THRESHOLD,
            # Friction as ODE and DART solve it: a pyramid, limited by mu along each of the two directions,
            # not Bullet's default cone (which also held wheels less firmly at rest).
            enableConeFriction=0,
            deterministicOverlappingPairs=1,
            physicsClientId=cid,
        )
        pb.setGravity(*physics.gravity, physicsClientId=cid)
        self.entities: dict[str, Entity] = {}
        # Headless: static plane visuals are drawn by the cameras themselves (see flat_planes.py).
        self.flat_planes: dict[str, list[FlatPlane]] = {}
        self._planes: list[FlatPlane] = []
        self._no_visual = -1
        self.mimics: dict[str, Mimics] = {}
        # (model, hook) run before every step; only models that need work every step add one.
        self._before_step: list[tuple[str, Callable[[], None]]] = []

    # --- entities ------------------------------------------------------------------------------------

    def add_model(self, model: Model) -> Entity:
        """Build `model` (poses as loaded, i.e. already at its spawn pose) and return its entity."""
        if model.name in self.entities:
            raise RuntimeFailure(f"an entity named {model.name!r} already exists", hint="choose another --name")
        plan = plan_model(model, split_colours=self.gui)
        bodies: list[int] = []
        self._planes = []
        try:
            for body_plan, flags in zip(plan.bodies, self_collision.body_flags(model, plan), strict=True):
                bodies.append(self._build_body(body_plan, static=model.static, flags=flags))
            self_collision.apply(self.client, model, plan, tuple(bodies))
        except Exception:
            for b in bodies:
                pb.removeBody(b, physicsClientId=self.client)
            raise
        entity = Entity(self.client, model, plan, tuple(bodies))
        try:
            mimics = Mimics(entity, self.step_s)
        except Exception:
            for b in bodies:
                pb.removeBody(b, physicsClientId=self.client)
            raise
        self.entities[model.name] = entity
        self.mimics[model.name] = mimics
        if mimics.servos:
            self._before_step.append((model.name, mimics.before_step))
        gravity_off = GravityOff(entity, self.physics.gravity)
        if gravity_off.weights:
            self._before_step.append((model.name, gravity_off.before_step))
        if self._planes:
            self.flat_planes[model.name] = self._planes
        return entity

    def all_flat_planes(self) -> list[FlatPlane]:
        return [p for planes in self.flat_planes.values() for p in planes]

    def remove(self, name: str) -> None:
        entity = self.entities.pop(name, None)
        if entity is None:
            raise RuntimeFailure(f"no entity named {name!r}", hint=f"entities: {', '.join(self.entities) or 'none'}")
        self.mimics.pop(name).close()
        self._before_step = [(m, hook) for m, hook in self._before_step if m != name]
        for b in entity.bodies:
            pb.removeBody(b, physicsClientId=self.client)
        self.flat_planes.pop(name, None)

    def reset(self) -> None:
        for e in self.entities.values():
            e.reset()
            self.mimics[e.name].reset()

    def step(self) -> None:
        for _, hook in self._before_step:
            hook()
        for e in self.entities.values():
            if e.settling:
                e.settle_holds()
            if e.pending_efforts:
                e.apply_efforts()
        pb.stepSimulation(physicsClientId=self.client)

    def close(self) -> None:
        if self.client >= 0:
            try:
                pb.disconnect(physicsClientId=self.client)
            except pb.error:
                pass
            self.client = -1

    # --- building ------------------------------------------------------------------------------------

    def _build_body(self, plan: BodyPlan, *, static: bool, flags: int = 0) -> int:
        cid = self.client
        base, links = plan.links[0], plan.links[1:]
        base_col = self._collision_shape(base.collisions, static or plan.static_base)
        base_visuals = base.visuals
        if not self.gui and plan.static_base:
            planes = [v for v in base_visuals if isinstance(v.geometry, Plane)]
            base_visuals = tuple(v for v in base_visuals if not isinstance(v.geometry, Plane))
            for v in planes:
                g = v.geometry
                pose = base.frame_world.compose(v.pose).compose(Pose((0.0, 0.0, 0.0), _quat_z_to(g.normal)))
                self._planes.append(FlatPlane.from_pose(pose, g.size_m, v.rgba))
        base_vis = self._visual_shape(base_visuals)
        kw: dict = {}
        if links:
            kw = {
                "linkMasses": [lp.mass_kg for lp in links],
                # (a massless link is a static body's: its meshes collide as triangle meshes, as the base's)
                "linkCollisionShapeIndices": [
                    self._collision_shape(lp.collisions, static or lp.mass_kg == 0.0) for lp in links
                ],
                "linkVisualShapeIndices": [self._visual_shape(lp.visuals) for lp in links],
                "linkPositions": [],
                "linkOrientations": [],
                "linkInertialFramePositions": [lp.inertial_frame.xyz for lp in links],
                "linkInertialFrameOrientations": [lp.inertial_frame.quat for lp in links],
                # createMultiBody counts the base as 0: PyBullet link i is index i + 1 here.
                "linkParentIndices": [lp.parent + 1 for lp in links],
                "linkJointTypes": [_JOINT_TYPES[lp.joint.type if lp.joint else "fixed"] for lp in links],
                "linkJointAxis": [lp.axis for lp in links],
            }
            for lp in links:
                parent_frame = plan.links[lp.parent + 1].frame_world
                rel = parent_frame.inverse().compose(lp.frame_world)
                kw["linkPositions"].append(rel.xyz)
                kw["linkOrientations"].append(rel.quat)
        body = pb.createMultiBody(
            baseMass=base.mass_kg,
            baseCollisionShapeIndex=base_col,
            baseVisualShapeIndex=base_vis,
            basePosition=base.frame_world.xyz,
            baseOrientation=base.frame_world.quat,
            baseInertialFramePosition=base.inertial_frame.xyz,
            baseInertialFrameOrientation=base.inertial_frame.quat,
            flags=flags,
            physicsClientId=cid,
            **kw,
        )
        if body < 0:
            raise DescriptionError("PyBullet refused to build the body (createMultiBody failed)")
        for index, lp in enumerate(plan.links, start=-1):
            self._dynamics(body, index, lp)
            if lp.gear is not None:
                self._roller(body, index, *lp.gear)
        return body

    def _roller(self, body: int, index: int, wheel: int, ratio: float) -> None:
        """A mecanum roller (mecanum_rollers.py): no friction along its own axis, turning with its wheel."""
        cid = self.client
        pb.changeDynamics(body, index, anisotropicFriction=[0.0, 1.0, 1.0], physicsClientId=cid)
        # btMultiBodyGearConstraint keeps q_roller + gearRatio · q_wheel at 0
        o = [0.0, 0.0, 0.0]
        c = pb.createConstraint(body, index, body, wheel, pb.JOINT_GEAR, [1.0, 0.0, 0.0], o, o, physicsClientId=cid)
        pb.changeConstraint(c, gearRatio=-ratio, erp=GEAR_ERP, maxForce=GEAR_MAX_FORCE, physicsClientId=cid)

    def _dynamics(self, body: int, index: int, lp: LinkPlan) -> None:
        cid = self.client
        kw: dict = {
            "lateralFriction": lp.surface.mu,
            "restitution": lp.surface.restitution,
            "rollingFriction": 0.0,
            "spinningFriction": 0.0,
        }
        if index < 0:
            # PyBullet damps base motion by default (0.04); Gazebo does not. Links reject these keys: passing
            # them (or maxJointVelocity) makes changeDynamics silently ignore the whole call.
            kw.update(linearDamping=0.0, angularDamping=0.0)
        if lp.mass_kg > 0.0:
            kw["localInertiaDiagonal"] = lp.inertia_diagonal
        joint = lp.joint
        if index >= 0 and joint is not None and joint.type != "fixed":
            kw["jointDamping"] = max(0.0, joint.dynamics.damping)
            if joint.type in ("revolute", "prismatic") and joint.limits.bounded:
                kw["jointLowerLimit"] = joint.limits.lower
                kw["jointUpperLimit"] = joint.limits.upper
        pb.changeDynamics(body, index, physicsClientId=cid, **kw)
        if index >= 0 and joint is not None and joint.type != "fixed":
            # PyBullet motorises every joint by default; Gazebo's joints are free except for their friction.
            if joint.type == "ball":
                pb.setJointMotorControlMultiDof(
                    body,
                    index,
                    pb.POSITION_CONTROL,
                    targetPosition=[0, 0, 0, 1],
                    positionGain=0,
                    velocityGain=1,
                    force=[max(0.0, joint.dynamics.friction)] * 3,
                    physicsClientId=cid,
                )
            else:
                pb.setJointMotorControl2(
                    body,
                    index,
                    pb.VELOCITY_CONTROL,
                    targetVelocity=0.0,
                    force=max(0.0, joint.dynamics.friction),
                    physicsClientId=cid,
                )

    def _collision_shape(self, shapes: tuple[ShapeSpec, ...], static: bool) -> int:
        if not shapes:
            return -1
        cid = self.client
        if len(shapes) == 1:
            kw = _shape_kwargs(shapes[0], collision=True, static=static)
            return pb.createCollisionShape(physicsClientId=cid, **kw)
        arrays = _shape_arrays(shapes, collision=True, static=static)
        return pb.createCollisionShapeArray(physicsClientId=cid, **arrays)

    def _visual_shape(self, shapes: tuple[ShapeSpec, ...]) -> int:
        cid = self.client
        if not shapes:
            # With no visual, PyBullet draws the collision shapes (a checkered ground, say); Gazebo draws
            # nothing. A speck no renderer resolves stands in.
            if self._no_visual < 0:
                self._no_visual = pb.createVisualShape(
                    pb.GEOM_SPHERE, radius=1e-5, rgbaColor=[0, 0, 0, 0], physicsClientId=cid
                )
            return self._no_visual
        if len(shapes) == 1:
            return pb.createVisualShape(physicsClientId=cid, **_shape_kwargs(shapes[0], collision=False))
        return pb.createVisualShapeArray(physicsClientId=cid, **_shape_arrays(shapes, collision=False))


def _plane_visual(spec: ShapeSpec, g: Plane) -> tuple[Vec3, Vec3, tuple[float, float, float, float]]:
    """(half extents, position, orientation) of the thin box drawn for a plane visual in a compound shape."""
    q = _quat_z_to(g.normal)
    t = PLANE_VISUAL_THICKNESS_M
    pose = spec.pose.compose(Pose((0.0, 0.0, -t / 2), q))
    return (g.size_m[0] / 2, g.size_m[1] / 2, t / 2), pose.xyz, pose.quat


def _quat_z_to(n: Vec3) -> tuple[float, float, float, float]:
    """The rotation taking +z onto the direction `n`."""
    nx, ny, nz = n
    norm = math.sqrt(nx * nx + ny * ny + nz * nz) or 1.0
    nx, ny, nz = nx / norm, ny / norm, nz / norm
    if nz < -0.999999:
        return (1.0, 0.0, 0.0, 0.0)
    x, y, z, w = -ny, nx, 0.0, 1.0 + nz
    s = math.sqrt(x * x + y * y + z * z + w * w)
    return (x / s, y / s, z / s, w / s)


def plane_quad(size_x_m: float, size_y_m: float) -> tuple[list[list[float]], list[int]]:
    """(vertices, triangle indices) of a centred rectangle in z = 0: two triangles, which TinyRenderer draws
    faster than the twelve of a thin box."""
    hx, hy = size_x_m / 2, size_y_m / 2
    return [[-hx, -hy, 0.0], [hx, -hy, 0.0], [hx, hy, 0.0], [-hx, hy, 0.0]], [0, 1, 2, 0, 2, 3]


def _shape_kwargs(spec: ShapeSpec, *, collision: bool, static: bool = False, single: bool = True) -> dict:
    g = spec.geometry
    frame = "collisionFrame" if collision else "visualFrame"
    kw: dict = {f"{frame}Position": spec.pose.xyz, f"{frame}Orientation": spec.pose.quat}
    if not collision:
        kw["rgbaColor"] = spec.rgba
    if isinstance(g, Box):
        kw.update(shapeType=pb.GEOM_BOX, halfExtents=[s / 2 for s in g.size_m])
    elif isinstance(g, Sphere):
        kw.update(shapeType=pb.GEOM_SPHERE, radius=g.radius_m)
    elif isinstance(g, Cylinder):
        kw.update(shapeType=pb.GEOM_CYLINDER, radius=g.radius_m)
        kw["height" if collision else "length"] = g.length_m
    elif isinstance(g, Capsule):
        kw.update(shapeType=pb.GEOM_CAPSULE, radius=g.radius_m)
        kw["height" if collision else "length"] = g.length_m
    elif isinstance(g, Plane):
        if collision:
            kw.update(shapeType=pb.GEOM_PLANE, planeNormal=g.normal)
        elif single:
            verts, idx = plane_quad(*g.size_m)
            pose = spec.pose.compose(Pose((0.0, 0.0, 0.0), _quat_z_to(g.normal)))
            kw.update(
                shapeType=pb.GEOM_MESH,
                vertices=verts,
                indices=idx,
                normals=[[0.0, 0.0, 1.0]] * len(verts),
                visualFramePosition=pose.xyz,
                visualFrameOrientation=pose.quat,
            )
        else:
            half, pos, orn = _plane_visual(spec, g)
            kw.update(shapeType=pb.GEOM_BOX, halfExtents=half, visualFramePosition=pos, visualFrameOrientation=orn)
    elif isinstance(g, Mesh):
        kw.update(shapeType=pb.GEOM_MESH, fileName=g.path, meshScale=g.scale)
        if collision and static:
            kw["flags"] = pb.GEOM_FORCE_CONCAVE_TRIMESH
    else:  # pragma: no cover - the loader only produces the geometries above
        raise DescriptionError(f"unsupported geometry {type(g).__name__}")
    return kw


def _shape_arrays(shapes: tuple[ShapeSpec, ...], *, collision: bool, static: bool = False) -> dict:
    frame = "collisionFrame" if collision else "visualFrame"
    out: dict = {
        "shapeTypes": [],
        "radii": [],
        "halfExtents": [],
        "lengths": [],
        "fileNames": [],
        "meshScales": [],
        "planeNormals": [],
        "flags": [],
        f"{frame}Positions": [],
        f"{frame}Orientations": [],
    }
    if not collision:
        out["rgbaColors"] = []
    for spec in shapes:
        kw = _shape_kwargs(spec, collision=collision, static=static, single=False)
        out["shapeTypes"].append(kw["shapeType"])
        out["radii"].append(kw.get("radius", 0.0))
        out["halfExtents"].append(list(kw.get("halfExtents", (0.0, 0.0, 0.0))))
        out["lengths"].append(kw.get("height", kw.get("length", 0.0)))
        out["fileNames"].append(kw.get("fileName", ""))
        out["meshScales"].append(list(kw.get("meshScale", (1.0, 1.0, 1.0))))
        out["planeNormals"].append(list(kw.get("planeNormal", (0.0, 0.0, 1.0))))
        out["flags"].append(kw.get("flags", 0))
        out[f"{frame}Positions"].append(list(kw[f"{frame}Position"]))
        out[f"{frame}Orientations"].append(list(kw[f"{frame}Orientation"]))
        if not collision:
            out["rgbaColors"].append(list(spec.rgba))
    return out
