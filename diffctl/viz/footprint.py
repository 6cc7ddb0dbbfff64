"""Top-down outlines of visual geometry: a 3D primitive at a pose, projected onto the fixed frame's XY plane.

Pure math. The page draws the robot as seen from above, so each box, cylinder, sphere or capsule becomes
the convex polygon it covers on the ground plane, plus the height of its top for drawing order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from diffctl.viz.transforms import Transform

CIRCLE_SEGMENTS = 16


@dataclass(frozen=True)
class Primitive:
    """A visual shape in its own frame: box (size_m = x, y, z), cylinder/capsule (radius_m, length_m along z),
    sphere (radius_m)."""

    kind: str
    size_m: tuple[float, float, float] = (0.0, 0.0, 0.0)
    radius_m: float = 0.0
    length_m: float = 0.0


@dataclass(frozen=True)
class Outline:
    points_xy_m: tuple[tuple[float, float], ...]
    top_z_m: float


def _circle(cx: float, cy: float, cz: float, r: float, axis_u, axis_v, n: int = CIRCLE_SEGMENTS):
    out = []
    for i in range(n):
        a = 2 * math.pi * i / n
        c, s = math.cos(a) * r, math.sin(a) * r
        out.append(tuple(ctr + c * u + s * v for ctr, u, v in zip((cx, cy, cz), axis_u, axis_v, strict=True)))
    return out


def convex_hull(points: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """Counter-clockwise hull (Andrew's monotone chain); collinear points dropped."""
    pts = sorted(set(points))
    if len(pts) <= 2:
        return pts

    def cross(o, a, b) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list[tuple[float, float]] = []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 1e-15:
            lower.pop()
        lower.append(p)
    upper: list[tuple[float, float]] = []
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 1e-15:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def surface_points(shape: Primitive) -> list[tuple[float, float, float]]:
    """Points in the shape's frame whose convex hull's projection is the shape's outline from any direction."""
    if shape.kind == "box":
        hx, hy, hz = (s / 2 for s in shape.size_m)
        return [(sx * hx, sy * hy, sz * hz) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    if shape.kind == "cylinder":
        h = shape.length_m / 2
        return _circle(0, 0, -h, shape.radius_m, (1, 0, 0), (0, 1, 0)) + _circle(
            0, 0, h, shape.radius_m, (1, 0, 0), (0, 1, 0)
        )
    raise ValueError(f"no surface points for {shape.kind!r}")


def outline(shape: Primitive, pose: Transform) -> Outline | None:
    """The ground-plane outline of `shape` placed at `pose`; None for shapes without one (meshes, planes)."""
    if shape.kind in ("box", "cylinder"):
        pts3 = [pose.apply(p) for p in surface_points(shape)]
        hull = convex_hull([(p[0], p[1]) for p in pts3])
        return Outline(tuple(hull), max(p[2] for p in pts3))
    if shape.kind == "sphere":
        c = pose.translation_m
        ring = _circle(c[0], c[1], 0.0, shape.radius_m, (1, 0, 0), (0, 1, 0))
        return Outline(tuple((p[0], p[1]) for p in ring), c[2] + shape.radius_m)
    if shape.kind == "capsule":
        h = shape.length_m / 2
        ends = [pose.apply((0, 0, -h)), pose.apply((0, 0, h))]
        ring: list[tuple[float, float]] = []
        for e in ends:
            ring += [(p[0], p[1]) for p in _circle(e[0], e[1], 0.0, shape.radius_m, (1, 0, 0), (0, 1, 0))]
        return Outline(tuple(convex_hull(ring)), max(e[2] for e in ends) + shape.radius_m)
    return None


def polygon_area_m2(points: tuple[tuple[float, float], ...]) -> float:
    n = len(points)
    return abs(sum(points[i][0] * points[(i + 1) % n][1] - points[(i + 1) % n][0] * points[i][1] for i in range(n))) / 2
