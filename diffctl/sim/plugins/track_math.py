"""Pure math of gz-sim's tracks: what each contact asks of the vehicle, and the motion those asks settle on.

gz-sim 8's TrackController gives each contact of a track a friction direction and a surface speed. With a
centre of rotation (TrackedVehicle's: on the body's y axis at v/ω, a fixed point in the world until the next
command), the direction is tangent to the circle about that centre through the contact; without one, it runs
along the track. Along it the track's surface moves at the track's speed, forwards where the track's bottom
meets the ground. So each contact asks the track's body to move, relative to what it touches, along that
circle at the track's speed: to turn about the centre at speed / distance (or, without a centre, to run along
the track at the track's speed).

The contacts' frictions then settle it: across the circles the second friction direction grips, so the body
turns about the centre; along them, each contact's friction (at most its load times mu) pulls the body towards
its asked rate, with a moment about the centre of load times distance. The body settles where the moments
balance (`settled_rate`): the weighted median of the asks under pure Coulomb friction; here friction grows
linearly with the slip up to `SLIP_SPEED_M_S`, as a solver's friction does, so the balance moves smoothly
where two tracks' moments nearly match instead of jumping from one track's rate to the other's. That one
motion is what every belt of the body then runs at (track_belts.py).

A physics engine shares the load between a track's contact points as its solver happens to (a rigid vehicle on
many points is statically indeterminate: the shares drift with the solver's history, and the balance with
them). The points are where gz-sim's would be (a box's corners, a roller's line), so they are kept
(`ContactPatch`), but the load is spread evenly along the touching tracks, each track taking a share by the
length its points span, and evenly between each track's points (`patch_asks`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from diffctl.description.model import Plugin
from diffctl.description.pose import Pose, quat_from_rpy
from diffctl.errors import DescriptionError

Vec3 = tuple[float, float, float]

# Contacts closer than this to the centre of rotation have no friction direction to speak of (gz's normalised
# zero vector): they ask nothing.
MIN_LEVER_M = 1e-4
# The slip (m/s) at which a contact's friction reaches its full load times mu.
SLIP_SPEED_M_S = 0.02


def _cross(a: Vec3, b: Vec3) -> Vec3:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _dot(a: Vec3, b: Vec3) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def track_forward(track_y: Vec3, normal: Vec3) -> Vec3:
    """The way a contact's surface pushes the body for a positive track speed: across the track's y axis and the
    contact normal (pointing into the track), as gz derives the belt direction; forwards under the track,
    backwards on its top."""
    return _cross(track_y, normal)


def asked_rate(
    point: Vec3, normal: Vec3, track_y: Vec3, speed_m_s: float, center: Vec3 | None
) -> tuple[float, float] | None:
    """(what the contact asks, its lever) for one contact of a track running at `speed_m_s`: with a centre of
    rotation the turn rate (rad/s, about `normal`) and the distance to the centre in the contact's plane; without
    one the speed along the track's forward direction and a lever of 1. None when it asks nothing."""
    forward = track_forward(track_y, normal)
    if center is None:
        return speed_m_s, 1.0
    r = (point[0] - center[0], point[1] - center[1], point[2] - center[2])
    along = _dot(r, normal)
    r = (r[0] - along * normal[0], r[1] - along * normal[1], r[2] - along * normal[2])
    lever = math.sqrt(_dot(r, r))
    if lever < MIN_LEVER_M:
        return None
    # the circle's tangent at the contact, turning positively about the normal
    tangent = _cross(normal, r)
    side = _dot(forward, tangent)
    if side == 0.0:
        return None
    # the body turning at rate w about the centre moves here at w·lever along the tangent; the track wants
    # speed along its forward direction, which the tangent follows or opposes
    return math.copysign(1.0, side) * speed_m_s / lever, lever


@dataclass(frozen=True)
class ContactPatch:
    """Where one track meets the ground: its contact points in the track plane's frame (`origin`, axes `x` along
    the tracks, `y` across them, `z` out of their plane), the ground's normal pointing into the track, and the
    load the track carries (N)."""

    points_m: tuple[Vec3, ...]
    normal: Vec3
    load_n: float = 0.0

    @property
    def length_m(self) -> float:
        """How far along the track its points reach."""
        xs = [p[0] for p in self.points_m]
        return max(xs) - min(xs)


def patch_asks(
    patch: ContactPatch,
    frame: tuple[Vec3, Vec3, Vec3, Vec3],
    speed_m_s: float,
    center: Vec3 | None,
) -> list[tuple[float, float, float]]:
    """(asked rate, load, lever) for each of the patch's points (`asked_rate`), the load shared evenly between
    them; `frame` is the track plane's origin and its x, y, z axes in the world."""
    origin, x_axis, y_axis, z_axis = frame
    share = patch.load_n / max(1, len(patch.points_m))
    asks = []
    for a, b, c in patch.points_m:
        point = tuple(origin[k] + a * x_axis[k] + b * y_axis[k] + c * z_axis[k] for k in range(3))
        ask = asked_rate(point, patch.normal, y_axis, speed_m_s, center)  # type: ignore[arg-type]
        if ask is not None:
            asks.append((ask[0], share, ask[1]))
    return asks


def settled_rate(asks: Iterable[tuple[float, float, float]], slip_m_s: float = SLIP_SPEED_M_S) -> float | None:
    """The rate at which the asks' friction moments about the centre balance: each (rate, load, lever) pulls with
    load · lever · s, s the slip lever · (its rate − the rate) over `slip_m_s`, clipped to ±1. None for no asks;
    with no load at all, the middle of the asked rates."""
    items = np.array(list(asks), dtype=float).reshape(-1, 3)
    if not len(items):
        return None
    rates, loads, levers = items.T
    lo, hi = float(rates.min()), float(rates.max())
    if loads.sum() <= 0.0:
        return (lo + hi) / 2.0
    moment, gain = loads * levers, levers / slip_m_s

    def pull(rate: float) -> float:
        return float(np.dot(moment, np.clip(gain * (rates - rate), -1.0, 1.0)))

    # the pull falls as the rate rises, from ≥ 0 at the lowest ask to ≤ 0 at the highest; where opposite pulls
    # both saturate it is zero over a span, any rate in which balances: its middle
    def edge(pulling_up: bool) -> float:
        a, b = lo, hi
        for _ in range(48):
            if b - a <= 1e-9 * max(1.0, abs(b)):
                break
            mid = (a + b) / 2.0
            p = pull(mid)
            if p > 0.0 or (pulling_up and p == 0.0):
                a = mid
            else:
                b = mid
        return (a + b) / 2.0

    return (edge(False) + edge(True)) / 2.0


def belt_joint_speeds(rate: float, center_xy: tuple[float, float] | None) -> tuple[float, float, float]:
    """The belt's speeds relative to its track (along the track's x, its y, and about its z) that keep the belt
    at rest on the ground while the track's body moves as the contacts settled: about the centre (given in the
    track's frame) at `rate` rad/s, or, without a centre, along the track's x at `rate` m/s."""
    if center_xy is None:
        return -rate, 0.0, 0.0
    cx, cy = center_xy
    # the body turning at rate about c moves the track's origin at rate·z×(0 − c); the belt moves the opposite way
    return -rate * cy, rate * cx, -rate


def track_orientation(plugin: Plugin, source: str = "") -> Pose:
    """TrackController's `<track_orientation>`: roll, pitch and yaw (as gz-math reads a quaternion) turning the
    link's frame into the track's, whose x axis the track runs along; none turns nothing."""
    text = plugin.get("track_orientation")
    if text is None:
        return Pose()
    try:
        values = [float(v) for v in text.split()]
    except ValueError:
        values = []
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise DescriptionError(
            f"plugin {plugin.name!r}: <track_orientation> {text!r} is not three finite numbers",
            source=source or None,
            field=f"plugin {plugin.filename}: track_orientation",
            hint="give roll pitch yaw in radians, e.g. 0 0 1.5708",
        )
    return Pose((0.0, 0.0, 0.0), quat_from_rpy(*values))
