"""The transform tree of a model: parent→child link transforms, fixed or as a function of a joint position.

Pure math on `description.Model`: a joint at position q moves its child about (or along) the joint axis,
which passes through the joint frame's origin; angles in radians, distances in metres.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from diffctl.description.model import Model
from diffctl.description.pose import Pose, Vec3, quat_from_axis_angle, quat_rotate

ROTATING = ("revolute", "continuous")


@dataclass(frozen=True)
class Segment:
    """One joint as TF sees it: the child link's pose in the parent link's frame."""

    joint: str
    type: str
    parent: str  # link name, or "world"
    child: str
    origin: Pose  # child in parent at position 0
    pivot_xyz: Vec3  # joint origin in the child frame
    axis_child: Vec3  # unit axis in the child frame (unused for fixed joints)

    @property
    def moves(self) -> bool:
        return self.type in (*ROTATING, "prismatic")

    def transform(self, position: float = 0.0) -> Pose:
        """Child pose in the parent frame with the joint at `position` (rad or m)."""
        if self.type in ROTATING:
            # A turn r about the axis through the pivot p is the rigid motion (p − r·p, r): one composition with
            # the origin per message (robot_state_publisher does this for every joint_states sample).
            spin = quat_from_axis_angle(self.axis_child, position)
            px, py, pz = self.pivot_xyz
            rx, ry, rz = quat_rotate(spin, self.pivot_xyz)
            return self.origin.compose(Pose((px - rx, py - ry, pz - rz), spin))
        if self.type == "prismatic":
            ax, ay, az = self.axis_child
            return self.origin * Pose((ax * position, ay * position, az * position))
        return self.origin


@dataclass(frozen=True)
class KinematicTree:
    root: str
    segments: tuple[Segment, ...]

    @staticmethod
    def from_model(model: Model) -> KinematicTree:
        segments = []
        for j in model.joints:
            child = model.link(j.child)
            # A joint to the world is expressed in the world frame, everything else in the model frame.
            if j.parent == "world":
                parent_pose, child_pose = Pose(), child.pose_world
            else:
                parent_pose, child_pose = model.link(j.parent).pose_model, child.pose_model
            segments.append(
                Segment(
                    joint=j.name,
                    type=j.type,
                    parent=j.parent,
                    child=j.child,
                    origin=parent_pose.inverse() * child_pose,
                    pivot_xyz=j.pose_child.xyz,
                    axis_child=j.axis_child or (0.0, 0.0, 1.0),
                )
            )
        return KinematicTree(model.root_link(), tuple(segments))

    def fixed(self) -> Iterator[Segment]:
        """Segments published once on /tf_static."""
        return (s for s in self.segments if s.type == "fixed")

    def unsupported(self) -> list[str]:
        """Joints with no single position (ball): like robot_state_publisher's floating joints, not published."""
        return [s.joint for s in self.segments if s.type not in (*ROTATING, "prismatic", "fixed")]

    def moving(self) -> dict[str, Segment]:
        return {s.joint: s for s in self.segments if s.moves}
