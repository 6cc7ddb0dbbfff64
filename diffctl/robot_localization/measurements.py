"""Sensor data into the filter's frames, as robot_localization prepares it before fusing.

Poses go to the world frame (absolute), to relative-to-first (relative) or to body velocities
(differential); twists and accelerations to the body frame, with the lever-arm terms of a sensor mounted
away from the body origin. The update vector follows the rotation: a variable configured for the sensor
counts wherever the rotation carries it. IMU orientation is special: its frame_id is the mounting frame,
so only the mounting's yaw rotates roll and pitch, and the mounting angles are removed from the reading.

Pure: frames are looked up through the `lookup(target, source, stamp_ns)` function the node passes in
(the transform taking `source` coordinates to `target`, or None when the tree cannot give it).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from diffctl.robot_localization.rotations import Rigid, from_quat, from_rpy, rot_z, to_rpy
from diffctl.robot_localization.state import AX, AZ, NAMES, PITCH, ROLL, STATE_SIZE, VPITCH, VROLL, VX, VZ, X, Z
from diffctl.robot_localization.state import wrap_angle as wrap

Lookup = Callable[[str, str, int], Rigid | None]
Warn = Callable[[str, str], None]  # (diagnostic key, message)
TWO_D = (Z, ROLL, PITCH, VZ, VROLL, VPITCH, AZ)
MASK_EPS = 1e-6


@dataclass
class Prepared:
    values: np.ndarray = field(default_factory=lambda: np.zeros(STATE_SIZE))
    covariance: np.ndarray = field(default_factory=lambda: np.zeros((STATE_SIZE, STATE_SIZE)))
    update: list[bool] = field(default_factory=lambda: [False] * STATE_SIZE)


def _rotated_mask(rot: np.ndarray, flags: list[bool]) -> list[bool]:
    """The update flags of three variables carried through a rotation: a row of rot·diag(flags) that is not
    (nearly) zero is a variable the sensor now measures."""
    m = rot * np.array([1.0 if f else 0.0 for f in flags])
    return [bool(np.linalg.norm(row) >= MASK_EPS) for row in m]


def _rot6(rot: np.ndarray) -> np.ndarray:
    r = np.zeros((6, 6))
    r[:3, :3] = rot
    r[3:, 3:] = rot
    return r


def force_two_d(p: Prepared) -> None:
    """two_d_mode: z, roll, pitch and their rates measured as exactly zero, so the filter keeps them there."""
    for i in TWO_D:
        p.values[i] = 0.0
        p.covariance[i, i] = 1e-6
        p.update[i] = True


class Preparer:
    """Per-sensor memory (previous poses for differential, first poses for relative) and the preparations."""

    def __init__(self, *, base_link: str, world_frame: str, two_d_mode: bool, gravity_mps2: float,
                 lookup: Lookup, warn: Warn | None = None) -> None:
        self.base_link = base_link
        self.world_frame = world_frame
        self.two_d_mode = two_d_mode
        self.gravity_mps2 = gravity_mps2
        self.lookup = lookup
        self.warn = warn
        self.previous: dict[str, tuple[Rigid, np.ndarray]] = {}
        self.initial: dict[str, Rigid] = {}

    def reset(self) -> None:
        self.previous.clear()
        self.initial.clear()

    def _lookup_safe(self, target: str, source: str, stamp_ns: int) -> Rigid | None:
        t = self.lookup(target, source, stamp_ns)
        if t is None and target == source:
            return Rigid.identity()
        return t

    def _copy_covariance(self, flat: list[float] | np.ndarray, topic: str, update: list[bool], offset: int,
                         dim: int) -> np.ndarray:
        cov = np.array(flat, dtype=float).reshape(dim, dim)
        if self.warn is not None:
            for i in range(dim):
                for j in range(dim):
                    v = cov[i, j]
                    if v > 1e3 and (update[offset + i] or update[offset + j]):
                        self.warn(f"{topic}_covariance",
                                  f"The covariance at position ({dim * i + j}), which corresponds to "
                                  f"{NAMES[offset + i]} variance, was large ({v}). Ensure that the value "
                                  "is accurate.")
                    elif update[i] and i == j and v == 0:
                        self.warn(f"{topic}_covariance",
                                  f"The covariance at position ({dim * i + j}), which corresponds to "
                                  f"{NAMES[offset + i]} variance, was zero. This will be replaced with a small "
                                  "value to maintain filter stability, but should be corrected at the message "
                                  "origin node.")
                    elif update[i] and i == j and v < 0:
                        self.warn(f"{topic}_covariance",
                                  f"The covariance at position ({dim * i + j}), which corresponds to "
                                  f"{NAMES[offset + i]} variance, was negative. This will be replaced with a "
                                  "small value to maintain filter stability, but should be corrected at the "
                                  "message origin node.")
        return cov

    # --- twist ------------------------------------------------------------------------------------------------
    def prepare_twist(self, topic: str, stamp_ns: int, frame_id: str, linear: np.ndarray, angular: np.ndarray,
                      covariance: list[float] | np.ndarray, update: list[bool], target_frame: str,
                      state_angular_velocity: np.ndarray) -> Prepared | None:
        """Body velocities in `target_frame`: rotated, plus the velocity a lever arm adds when turning."""
        msg_frame = frame_id or target_frame
        cov = self._copy_covariance(covariance, topic, update, VX, 6)
        t = self._lookup_safe(target_frame, msg_frame, stamp_ns)
        if t is None:
            return None
        out = Prepared(update=list(update))
        ang = t.rot @ angular
        lin = t.rot @ linear + np.cross(t.trans, state_angular_velocity)
        out.update[VX:VX + 3] = _rotated_mask(t.rot, update[VX:VX + 3])
        out.update[VROLL:VROLL + 3] = _rotated_mask(t.rot, update[VROLL:VROLL + 3])
        r6 = _rot6(t.rot)
        out.values[VX:VX + 3] = lin
        out.values[VROLL:VROLL + 3] = ang
        out.covariance[VX:VX + 6, VX:VX + 6] = r6 @ cov @ r6.T
        if self.two_d_mode:
            force_two_d(out)
        return out

    # --- acceleration -----------------------------------------------------------------------------------------
    def prepare_acceleration(self, topic: str, stamp_ns: int, frame_id: str, accel: np.ndarray,
                             covariance: list[float] | np.ndarray, update: list[bool], target_frame: str,
                             relative: bool, remove_gravity: bool, orientation: tuple[float, float, float, float]
                             | None, state: np.ndarray, angular_acceleration: np.ndarray) -> Prepared | None:
        """Linear acceleration in the body frame, the lever-arm terms and (if asked) gravity removed.
        `orientation` is the IMU's (None when the message says it has none)."""
        msg_frame = frame_id or self.base_link
        cov = self._copy_covariance(covariance, topic, update, AX, 3)
        t = self._lookup_safe(target_frame, msg_frame, stamp_ns)
        if t is None:
            return None
        w = state[VROLL:VROLL + 3]
        acc = t.rot @ accel + np.cross(t.trans, angular_acceleration) - np.cross(np.cross(t.trans, w), w)
        if remove_gravity:
            g = np.array((0.0, 0.0, self.gravity_mps2))
            if orientation is None:
                basis = from_rpy(state[ROLL], state[PITCH], state[PITCH + 1]) @ t.rot
                acc = acc - basis.T @ g
            else:
                x, y, z, qw = orientation
                norm = math.sqrt(x * x + y * y + z * z + qw * qw)
                attitude = from_quat(x / norm, y / norm, z / norm, qw / norm) if norm > 0 else np.eye(3)
                acc = acc - (attitude.T @ g if not relative else t.rot.T @ attitude.T @ g)
        out = Prepared(update=list(update))
        out.update[AX:AX + 3] = _rotated_mask(t.rot, update[AX:AX + 3])
        out.values[AX:AX + 3] = acc
        out.covariance[AX:AX + 3, AX:AX + 3] = t.rot @ cov @ t.rot.T
        if self.two_d_mode:
            force_two_d(out)
        return out

    # --- pose -------------------------------------------------------------------------------------------------
    def prepare_pose(self, topic: str, stamp_ns: int, frame_id: str, position: tuple[float, float, float],
                     orientation: tuple[float, float, float, float], covariance: list[float] | np.ndarray,
                     update: list[bool], *, target_frame: str, source_frame: str, differential: bool,
                     relative: bool, imu: bool, last_stamp_ns: int,
                     state_angular_velocity: np.ndarray) -> Prepared | None:
        """A pose in the world frame (or, differential, the velocity between two poses, in the body frame)."""
        if target_frame == "":
            final_target = frame_id or self.world_frame
            pose_frame = final_target
        else:
            final_target = target_frame
            pose_frame = final_target if (differential and not imu) else frame_id
        update = list(update)
        if orientation == (0.0, 0.0, 0.0, 0.0):
            q = (0.0, 0.0, 0.0, 1.0)
            if any(update[ROLL:ROLL + 3]) and self.warn is not None:
                self.warn(f"{topic}_orientation",
                          f"The {topic} message contains an invalid orientation quaternion, but its "
                          "configuration is such that orientation data is being used. Correcting...")
        else:
            x, y, z, w = orientation
            n = math.sqrt(x * x + y * y + z * z + w * w)
            q = (x / n, y / n, z / n, w / n) if abs(n - 1.0) > 0.01 else orientation
        pose = Rigid(from_quat(*q), np.array(position, dtype=float))
        target = self._lookup_safe(final_target, pose_frame, stamp_ns)
        source = self._lookup_safe(source_frame, self.base_link, stamp_ns) if source_frame != self.base_link \
            else None
        if target is None:
            return None
        if imu:
            # An IMU's frame_id is where it is mounted, not the frame of its orientation: only the
            # mounting's yaw turns which body axes its roll and pitch are about.
            mount_yaw = to_rpy(target.rot)[2]
            turn = rot_z(mount_yaw)
        else:
            turn = target.rot
        update[X:X + 3] = _rotated_mask(turn, update[X:X + 3])
        update[ROLL:ROLL + 3] = _rotated_mask(turn, update[ROLL:ROLL + 3])
        cov = self._copy_covariance(covariance, topic, update, X, 6)
        if source is not None:
            r6 = _rot6(source.rot)
            cov = r6.T @ cov @ r6
        rot6 = _rot6(turn)
        cov_rotated = rot6 @ cov @ rot6.T
        if imu:
            mount = to_rpy(target.rot)
            meas = to_rpy(pose.rot)
            rpy = np.array([wrap(meas[i] - mount[i]) for i in range(3)])
            rpy = rot_z(mount[2]) @ rpy
            pose = Rigid(from_rpy(*rpy), pose.trans)
            target = Rigid.identity()
        if differential:
            return self._differential(topic, stamp_ns, pose, cov, rot6, target, update, source_frame,
                                      last_stamp_ns, state_angular_velocity)
        if source is not None:
            pose = pose * source
        if relative:
            first = self.initial.setdefault(topic, pose)
            pose = first.inverse() * pose
        pose = target * pose
        out = Prepared(update=update)
        out.values[X:X + 3] = pose.trans
        out.values[ROLL:ROLL + 3] = pose.rpy()
        out.covariance[:6, :6] = cov_rotated
        if self.two_d_mode:
            force_two_d(out)
        return out

    def _differential(self, topic: str, stamp_ns: int, pose: Rigid, cov: np.ndarray, rot6: np.ndarray,
                      target: Rigid, update: list[bool], source_frame: str, last_stamp_ns: int,
                      state_angular_velocity: np.ndarray) -> Prepared | None:
        """The change since this sensor's previous pose, as body velocities over the time between them."""
        prepared = None
        previous = self.previous.get(topic)
        if previous is not None:
            prev_pose, prev_cov = previous
            delta = prev_pose.inverse() * pose
            delta = Rigid(target.rot, np.zeros(3)) * delta
            dt = (stamp_ns - last_stamp_ns) * 1e-9
            lin = delta.trans / dt
            ang = np.array(delta.rpy()) / dt
            twist_update = [False] * STATE_SIZE
            twist_update[VX:VX + 6] = update[X:X + 6]
            twist_cov = (rot6 @ cov @ rot6.T + rot6 @ prev_cov @ rot6.T) * dt
            prepared = self.prepare_twist(f"{topic}_twist", stamp_ns, source_frame, lin, ang, twist_cov.ravel(),
                                          twist_update, self.base_link, state_angular_velocity)
        self.previous[topic] = (pose, cov)
        return prepared
