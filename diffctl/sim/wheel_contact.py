"""How a wheel's cylinder meets the ground in Bullet: a rounded contact disc plus a slightly smaller core.

Why (measured, tests/sim/test_idle_creep.py): Bullet makes one contact point per convex shape and step and
keeps earlier points (its persistent manifold) until they drift ~1 mm. A cylinder lying on its side touches
the ground along a line; its support point is one rim or the other by the sign of a component that is zero
but for round-off. At any heading but the world axes that sign flips from step to step, so the manifold holds
one point per rim and refreshes only one of them: the other stays glued to the turning wheel, behind or ahead
of the axle, and carries the load there. A free wheel on it is an inverted pendulum: an idle tutorial car with
free wheels and a frictionless caster rolled 2.8 m a minute at yaw 0.7 rad (at yaw 0 the round-off is exact
and one rim is always chosen). Gazebo's ODE and DART regenerate all contacts every step and do not show it.

The fix keeps contacts fresh instead of changing how anything moves: a cylinder that turns about its own axis
on a revolute joint (a wheel, a roller) meets the world through
- a disc of the wheel's radius, as thick as twice Bullet's collision margin: its flat core has no thickness,
  so its lowest point is unique in every direction across the axis and is the one point its manifold keeps,
  replaced every step, under the axle;
- the cylinder's full width with a radius `CORE_RADIUS_SHARE` smaller, for sides and edges, which never
  reaches flat ground the disc stands on.
Visuals, mass and inertia are the SDF's; only the collision shapes change.
"""

from __future__ import annotations

from diffctl.description.model import Cylinder
from diffctl.description.pose import Pose, Vec3

# PyBullet gives every primitive shape a 1 mm collision margin (its default, not settable per shape): a
# cylinder's flat core is its half length minus that margin, so a 2 mm long one is a disc with rounded edges.
BULLET_MARGIN_M = 0.001
DISC_LENGTH_M = 2 * BULLET_MARGIN_M
# The core's radius is this share smaller than the wheel's: more than Bullet's contact-breaking distance
# (0.02 of a shape's bounding radius), so the core's rims make no contact points of their own on the ground.
CORE_RADIUS_SHARE = 0.05
# A cylinder counts as turning about its own axis when the joint axis is this close to it.
AXIS_TOLERANCE = 1e-6
AXIS_OFFSET_TOLERANCE_M = 1e-6


def rolls_about_own_axis(cylinder_pose: Pose, joint_axis: Vec3) -> bool:
    """Whether a cylinder at `cylinder_pose` (in the joint's frame) spins about its own axis on a joint
    whose axis is `joint_axis` through the frame's origin."""
    ax = _unit(joint_axis)
    if ax is None:
        return False
    own = cylinder_pose.rotate((0.0, 0.0, 1.0))
    if abs(abs(_dot(own, ax)) - 1.0) > AXIS_TOLERANCE:
        return False
    c = cylinder_pose.xyz
    along = _dot(c, ax)
    off = (c[0] - along * ax[0], c[1] - along * ax[1], c[2] - along * ax[2])
    return _dot(off, off) ** 0.5 <= AXIS_OFFSET_TOLERANCE_M


def wheel_parts(cylinder: Cylinder) -> tuple[Cylinder, Cylinder] | None:
    """(contact disc, core) for a wheel cylinder at the same pose, or None when it is thin enough already."""
    if cylinder.length_m <= DISC_LENGTH_M:
        return None
    disc = Cylinder(radius_m=cylinder.radius_m, length_m=DISC_LENGTH_M)
    core = Cylinder(radius_m=cylinder.radius_m * (1.0 - CORE_RADIUS_SHARE), length_m=cylinder.length_m)
    return disc, core


def _dot(a: Vec3, b: Vec3) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _unit(v: Vec3) -> Vec3 | None:
    n = _dot(v, v) ** 0.5
    if n == 0.0:
        return None
    return (v[0] / n, v[1] / n, v[2] / n)
