"""Rigid transforms and a small TF buffer: what the visualizer needs to place frames in the fixed frame.

Pure math, no bus. A `Transform` is the pose of a child frame in its parent (translation in metres, unit
quaternion xyzw), as in geometry_msgs/Transform. The buffer keeps the latest transform per child frame,
like tf2 with a cache of one: a visualizer draws the present, it does not interpolate the past.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from diffctl.description.pose import Quat, Vec3, quat_from_rpy, quat_multiply, quat_rotate
from diffctl.description.pose import quat_normalize as _normalize

__all__ = ["Quat", "Vec3", "quat_from_rpy", "quat_multiply", "quat_normalize", "quat_rotate", "yaw_of"]


def quat_normalize(q: Sequence[float]) -> Quat:
    try:
        return _normalize(q)
    except ValueError:
        # tf2 rejects such quaternions; identity keeps a bad message from poisoning the whole tree.
        return (0.0, 0.0, 0.0, 1.0)


def yaw_of(q: Quat) -> float:
    x, y, z, w = q
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


@dataclass(frozen=True)
class Transform:
    """Pose of a child frame in its parent frame."""

    translation_m: Vec3 = (0.0, 0.0, 0.0)
    rotation: Quat = (0.0, 0.0, 0.0, 1.0)

    @staticmethod
    def from_xyz_rpy(x_m: float, y_m: float, z_m: float, roll: float = 0, pitch: float = 0, yaw: float = 0):
        return Transform((x_m, y_m, z_m), quat_from_rpy(roll, pitch, yaw))

    def compose(self, other: Transform) -> Transform:
        """self ∘ other: `other` expressed in self's child frame, returned in self's parent frame."""
        t = quat_rotate(self.rotation, other.translation_m)
        return Transform(
            (self.translation_m[0] + t[0], self.translation_m[1] + t[1], self.translation_m[2] + t[2]),
            quat_normalize(quat_multiply(self.rotation, other.rotation)),
        )

    def inverse(self) -> Transform:
        x, y, z, w = self.rotation
        inv_q = (-x, -y, -z, w)
        t = quat_rotate(inv_q, self.translation_m)
        return Transform((-t[0], -t[1], -t[2]), inv_q)

    def apply(self, point: Sequence[float]) -> Vec3:
        r = quat_rotate(self.rotation, point)
        return (r[0] + self.translation_m[0], r[1] + self.translation_m[1], r[2] + self.translation_m[2])

    @property
    def yaw_rad(self) -> float:
        return yaw_of(self.rotation)

    def rotation_matrix(self) -> tuple[Vec3, Vec3, Vec3]:
        x, y, z, w = self.rotation
        return (
            (1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)),
            (2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)),
            (2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)),
        )

    def is_finite(self) -> bool:
        return all(math.isfinite(c) for c in (*self.translation_m, *self.rotation))


IDENTITY = Transform()


def strip_frame(name: str) -> str:
    # tf2 frame ids carry no leading slash; old publishers still send "/odom".
    return name[1:] if name.startswith("/") else name


class TfBuffer:
    """Latest transform per child frame, static and dynamic kept apart as /tf_static and /tf are."""

    def __init__(self) -> None:
        self._parent: dict[str, str] = {}
        self._tf: dict[str, Transform] = {}
        self._static: set[str] = set()

    def set(self, parent: str, child: str, transform: Transform, *, static: bool = False) -> bool:
        """Store one edge; refuses non-finite transforms, self-loops and edges that would close a cycle."""
        parent, child = strip_frame(parent), strip_frame(child)
        if not parent or not child or parent == child or not transform.is_finite():
            return False
        if self._would_cycle(parent, child):
            return False
        if not static and child in self._static and self._parent.get(child) == parent:
            # A dynamic update of a static edge would flicker between publishers; tf2 keeps both, we keep static.
            return False
        self._parent[child] = parent
        self._tf[child] = Transform(transform.translation_m, quat_normalize(transform.rotation))
        if static:
            self._static.add(child)
        else:
            self._static.discard(child)
        return True

    def _would_cycle(self, parent: str, child: str) -> bool:
        f: str | None = parent
        seen = 0
        while f is not None and seen < 10_000:
            if f == child:
                return True
            f = self._parent.get(f)
            seen += 1
        return False

    def clear_dynamic(self) -> None:
        """Forget /tf edges (after a jump back in sim time), keep /tf_static as tf2 does."""
        for child in [c for c in self._parent if c not in self._static]:
            del self._parent[child]
            del self._tf[child]

    def frames(self) -> list[str]:
        names = set(self._parent) | set(self._parent.values())
        return sorted(names)

    def parents(self) -> dict[str, str]:
        return dict(self._parent)

    def root_pose(self, frame: str) -> tuple[str, Transform]:
        """(root of `frame`'s tree, pose of `frame` in it); an unknown frame is its own root."""
        return self._to_root(strip_frame(frame))

    def _to_root(self, frame: str) -> tuple[str, Transform]:
        """(root frame, pose of `frame` in that root)."""
        pose = IDENTITY
        f = frame
        for _ in range(10_000):
            parent = self._parent.get(f)
            if parent is None:
                return f, pose
            pose = self._tf[f].compose(pose)
            f = parent
        return f, pose  # unreachable: set() refuses cycles

    def lookup(self, target: str, source: str) -> Transform | None:
        """Pose of `source` in `target` (tf2's lookupTransform(target, source)), None when not connected."""
        target, source = strip_frame(target), strip_frame(source)
        if target == source:
            return IDENTITY
        root_s, pose_s = self._to_root(source)
        root_t, pose_t = self._to_root(target)
        if root_s != root_t:
            return None
        return pose_t.inverse().compose(pose_s)

    def all_in(self, target: str) -> dict[str, Transform]:
        """Every frame connected to `target`, as its pose in `target`."""
        target = strip_frame(target)
        root_t, pose_t = self._to_root(target)
        inv_t = pose_t.inverse()
        out: dict[str, Transform] = {}
        for f in self.frames():
            root, pose = self._to_root(f)
            if root == root_t:
                out[f] = inv_t.compose(pose)
        if target not in out:
            out[target] = IDENTITY
        return out


def transform_points_xy(tf: Transform, xs: Iterable[float], ys: Iterable[float], z_m: float = 0.0) -> list[float]:
    """Points of a plane (z = z_m) mapped by `tf` and flattened to [x0, y0, x1, y1, …] in the target's XY."""
    out: list[float] = []
    for x, y in zip(xs, ys, strict=True):
        p = tf.apply((x, y, z_m))
        out.append(p[0])
        out.append(p[1])
    return out
