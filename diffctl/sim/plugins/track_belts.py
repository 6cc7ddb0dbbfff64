"""The belts under one model's tracks, run each step so the vehicle moves as gz-sim's track contacts move it.

PyBullet has no moving contact surfaces. Each track's collisions ride on a belt (sim/body_plan.py) that can
slide along the track's x and y and turn about its z. Every step, for the tracks of one body that share a
centre of rotation, the contacts the last step left (points, normals, normal forces) say what motion gz-sim's
contact rule settles on (track_math.py); each belt is put back under its track and set moving, relative to
it, opposite to that motion. Where a belt touches the ground it then stands still while the body moves as
gz-sim's would; friction still limits what the belts transmit (a blocked or lifted vehicle slips or spins).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pybullet as pb

from diffctl.description.pose import quat_rotate
from diffctl.sim.entity import Belt, Entity
from diffctl.sim.plugins.base import PluginContext, SystemPlugin
from diffctl.sim.plugins.track_controller import TrackController
from diffctl.sim.plugins.track_math import ContactPatch, Vec3, belt_joint_speeds, patch_asks, settled_rate

# The belts' motors: strong enough that only the ground's friction limits what a track transmits.
BELT_MAX_FORCE_N = 1e5
# How often the contacts are read again to settle the motion (sooner when a track's speed or centre changes):
# the settled motion only moves as the contacts do.
SETTLE_PERIOD_S = 0.01
# The share of the newly read load taken into the smoothed one at each settling (about 0.05 s of memory).
LOAD_SMOOTHING = 0.2
# The shortest length a touching patch counts with (a track touching at a point still carries).
MIN_PATCH_M = 0.01


class _BeltState:
    __slots__ = ("belt", "due", "key", "load_n", "moving", "speeds", "tracks")

    def __init__(self, belt: Belt, tracks: list[TrackController]) -> None:
        self.belt, self.tracks = belt, tracks
        self.key: tuple = ()
        self.speeds = (0.0, 0.0, 0.0)
        self.due = 0
        self.moving = True  # (set at rest once at the start)
        self.load_n = 0.0  # what the tracks carry, smoothed


class TrackBelts(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, tracks: list[TrackController]) -> None:
        self.ctx, self.entity = ctx, entity
        self._period = max(1, round(SETTLE_PERIOD_S * 1e9 / ctx.stepper.step_ns))
        by_belt: dict[int, _BeltState] = {}
        for t in tracks:
            if t.belt is not None:
                by_belt.setdefault(id(t.belt), _BeltState(t.belt, [])).tracks.append(t)
        self._belts = list(by_belt.values())
        # each belt's chain origin, axes and track centres in its carrier's centre-of-mass frame (PyBullet's)
        self._geometry: dict[int, tuple[Vec3, tuple[Vec3, ...], list[Vec3]]] = {}
        for state in self._belts:
            belt = state.belt
            com_to_frame = entity.inertial_frame(belt.body, belt.carrier).inverse()
            axes = tuple(com_to_frame.rotate(a) for a in belt.axes)
            centres = [com_to_frame.transform_point(belt.centres[t.link]) for t in state.tracks]
            self._geometry[id(belt)] = (com_to_frame.xyz, axes, centres)
        if self._belts:
            ctx.stepper.step_hooks.append(self._step)

    def _step(self) -> None:
        cid = self.entity.client
        for state in self._belts:
            # (tracks on one belt share their first one's centre: one rigid belt realises one motion)
            center = state.tracks[0].center
            key = (center, *(t.speed for t in state.tracks))
            if key != state.key or state.due <= 0:
                state.key, state.due = key, self._period
                speeds = self._settle(state, center)
                if speeds != state.speeds:
                    state.speeds = speeds
                    self._motors(state.belt, speeds)
            state.due -= 1
            still = state.speeds == (0.0, 0.0, 0.0)
            if still and not state.moving:
                continue  # at rest and put back already: the motors hold it
            state.moving = not still
            # back under the tracks, moving relative to them as settled
            b = state.belt
            pb.resetJointStatesMultiDof(
                b.body, list(b.joints), [[0.0]] * 3, [[v] for v in state.speeds], physicsClientId=cid
            )

    def _settle(self, state: _BeltState, center: Vec3 | None) -> tuple[float, float, float]:
        """The belt's speeds for the motion the tracks' contacts settle on (track_math.py)."""
        belt, tracks = state.belt, state.tracks
        if center is None and all(t.speed == 0.0 for t in tracks):
            return (0.0, 0.0, 0.0)
        cid, body = self.entity.client, belt.body
        if belt.carrier < 0:
            pos, orn = pb.getBasePositionAndOrientation(body, physicsClientId=cid)
        else:
            pos, orn = pb.getLinkState(body, belt.carrier, physicsClientId=cid)[:2]
        origin, axes, centres = self._geometry[id(belt)]
        o = quat_rotate(orn, origin)
        frame = ((pos[0] + o[0], pos[1] + o[1], pos[2] + o[2]), *(quat_rotate(orn, a) for a in axes))
        places = [_local(frame, _add(pos, quat_rotate(orn, c))) for c in centres]
        touching: list[list[tuple[Vec3, Vec3, float]]] = [[] for _ in tracks]
        for c in pb.getContactPoints(bodyA=body, physicsClientId=cid):
            if c[3] not in belt.links or c[2] == body:
                continue
            # the track whose collisions are nearest; the point and normal are the other body's, whose normal
            # points into the track as gz turns it
            p = _local(frame, c[6])
            nearest = min(range(len(places)), key=lambda i: sum((places[i][k] - p[k]) ** 2 for k in range(3)))
            touching[nearest].append((p, c[7], c[9]))
        # the vehicle's load, smoothed, spread evenly along the patches that touch (see track_math.py)
        load = sum(f for contacts in touching for _, _, f in contacts)
        state.load_n += LOAD_SMOOTHING * (load - state.load_n)
        patches: list[tuple[TrackController, ContactPatch]] = []
        for track, contacts in zip(tracks, touching, strict=True):
            if contacts:
                n = len(contacts)
                normal = tuple(sum(c[1][k] for c in contacts) / n for k in range(3))
                patches.append((track, ContactPatch(tuple(c[0] for c in contacts), normal)))  # type: ignore[arg-type]
        if not patches:
            # nothing touches: what the tracks' centres would ask, to start from when they land
            patches = [(t, ContactPatch((place,), frame[3])) for t, place in zip(tracks, places, strict=True)]
        lengths = [max(p.length_m, MIN_PATCH_M) for _, p in patches]
        total = sum(lengths)
        load_n = state.load_n if state.load_n > 0.0 else 1.0
        asks = [
            patch_asks(dataclasses.replace(patch, load_n=load_n * length / total), frame, track.speed, center)
            for (track, patch), length in zip(patches, lengths, strict=True)
        ]
        rate = settled_rate(np.concatenate(asks)) or 0.0
        local = None if center is None else _local(frame, center)[:2]
        return belt_joint_speeds(rate, local)  # type: ignore[arg-type]

    def _motors(self, belt: Belt, speeds: tuple[float, float, float]) -> None:
        pb.setJointMotorControlArray(
            belt.body,
            list(belt.joints),
            pb.VELOCITY_CONTROL,
            targetVelocities=list(speeds),
            forces=[BELT_MAX_FORCE_N] * 3,
            physicsClientId=self.entity.client,
        )

    def reset(self) -> None:
        for state in self._belts:
            state.key, state.speeds, state.moving = (), (0.0, 0.0, 0.0), True
            state.load_n = 0.0
            self._motors(state.belt, state.speeds)

    def close(self) -> None:
        if self._step in self.ctx.stepper.step_hooks:
            self.ctx.stepper.step_hooks.remove(self._step)


def _add(a: Vec3, b: Vec3) -> Vec3:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _local(frame: tuple[Vec3, Vec3, Vec3, Vec3], point: Vec3) -> Vec3:
    """A world point in the track plane's coordinates."""
    origin, *axes = frame
    r = (point[0] - origin[0], point[1] - origin[1], point[2] - origin[2])
    return tuple(r[0] * a[0] + r[1] * a[1] + r[2] * a[2] for a in axes)  # type: ignore[return-value]
