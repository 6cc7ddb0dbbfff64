"""Mecanum and omni wheels in Bullet: a wheel contact that grips along one direction only becomes a roller.

Gazebo models a mecanum wheel by its contact, not its rollers: the collision's `<fdir1>` (in a frame fixed to
the chassis, `gz:expressed_in`) is the direction `mu` acts along, and `mu2` ~ 0 lets the wheel slide freely
across it (gz-sim's examples/worlds/mecanum_drive.sdf). Bullet's friction is isotropic but for a per-axis scaling
in the colliding link's own frame, which for a spinning wheel turns with it. So such a contact is carried by a
sphere of the wheel's radius on a link of its own, the roller, hung from the wheel's parent on a revolute joint
about the free direction f (horizontal, fixed to the chassis) and geared to the wheel joint:
- spinning about f, the sphere's lowest point moves along the grip direction g = f × up only, and the roller
  link's anisotropic friction, zero along its axis f, leaves motion along f free;
- the gear ratio makes that motion along g what the wheel's own spin would give there:
  ω_roller · ((f × up) · g) = ω_wheel · ((a × up) · g), a the wheel axis.
The wheel keeps its joint, visuals and (most of its) mass; the controller and the joint states see it as before.
"""

from __future__ import annotations

import math

from diffctl.description.model import Surface
from diffctl.description.pose import Pose, Vec3

# A contact rolls freely across its friction direction when its cross friction is at most this share.
ROLLER_ANISOTROPY = 0.1
# The share of the wheel's mass (and inertia) the roller link takes.
ROLLER_MASS_SHARE = 0.1
UP: Vec3 = (0.0, 0.0, 1.0)


def is_roller_surface(surface: Surface) -> bool:
    grip, cross = max(surface.mu, surface.mu2), min(surface.mu, surface.mu2)
    return surface.fdir1 is not None and grip > 0 and cross <= ROLLER_ANISOTROPY * grip


def roller_frame(
    center_world: Vec3, fdir1_world: Vec3, wheel_axis_world: Vec3, mu_along_fdir1: bool
) -> tuple[Pose, float] | None:
    """(the roller's frame: x the free direction f, z up; its speed ÷ the wheel's), or None when the grip
    direction is vertical or the wheel cannot turn the roller (its axis along the grip)."""
    g = fdir1_world if mu_along_fdir1 else _cross(UP, fdir1_world)
    g = _unit((g[0], g[1], 0.0))
    if g is None:
        return None
    f = _cross(g, UP)  # horizontal, free direction: g = f × up
    roller_push = _dot(_cross(f, UP), g)
    wheel_push = _dot(_cross(wheel_axis_world, UP), g)
    if abs(wheel_push) < 1e-6 or abs(roller_push) < 1e-9:
        return None
    y = _cross(UP, f)
    return Pose(center_world, _quat_from_axes(f, y, UP)), wheel_push / roller_push


def _quat_from_axes(x: Vec3, y: Vec3, z: Vec3) -> tuple[float, float, float, float]:
    """The rotation whose columns are the unit axes x, y, z (a right-handed orthonormal frame)."""
    m00, m10, m20 = x
    m01, m11, m21 = y
    m02, m12, m22 = z
    trace = m00 + m11 + m22
    if trace > 0:
        s = 2.0 * math.sqrt(trace + 1.0)
        return ((m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25 * s)
    if m00 > m11 and m00 > m22:
        s = 2.0 * math.sqrt(1.0 + m00 - m11 - m22)
        return (0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s)
    if m11 > m22:
        s = 2.0 * math.sqrt(1.0 + m11 - m00 - m22)
        return ((m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s)
    s = 2.0 * math.sqrt(1.0 + m22 - m00 - m11)
    return ((m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s)


def _cross(a: Vec3, b: Vec3) -> Vec3:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _dot(a: Vec3, b: Vec3) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _unit(v: Vec3) -> Vec3 | None:
    n = math.sqrt(_dot(v, v))
    return None if n < 1e-9 else (v[0] / n, v[1] / n, v[2] / n)
