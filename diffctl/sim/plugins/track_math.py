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


def track_forward(track_y: Vec3, normal: Vec3) -> Vec3:
    """The way a contact's surface pushes the body for a positive track speed: across the track's y axis and the
    contact normal (pointing into the track), as gz derives the belt direction; forwards under the track,
    backwards on its top."""
    return _cross(track_y, normal)


def _asks(
    points: np.ndarray, normal: Vec3, track_y: Vec3, speed_m_s: float, center: Vec3 | None
) -> tuple[np.ndarray, np.ndarray]:
    """(asked rates, levers) of the contacts at `points` (n x 3, in the world) that ask something."""
    if center is None:
        return np.full(len(points), float(speed_m_s)), np.ones(len(points))
    n = np.asarray(normal, dtype=float)
    r = points - np.asarray(center, dtype=float)
    r -= np.outer(r @ n, n)  # into the contact's plane
    levers = np.linalg.norm(r, axis=1)
    # which way the track's forward push runs along the circle's tangent (n x r, turning positively about the
    # normal): forward · (n x r) = r · (forward x n)
    side = r @ np.array(_cross(track_forward(track_y, normal), normal))
    keep = (levers >= MIN_LEVER_M) & (side != 0.0)
    # the body turning at rate w about the centre moves a contact at w·lever along the tangent
    return np.sign(side[keep]) * speed_m_s / levers[keep], levers[keep]


def asked_rate(
    point: Vec3, normal: Vec3, track_y: Vec3, speed_m_s: float, center: Vec3 | None
) -> tuple[float, float] | None:
    """(what the contact asks, its lever) for one contact of a track running at `speed_m_s`: with a centre of
    rotation the turn rate (rad/s, about `normal`) and the distance to the centre in the contact's plane; without
    one the speed along the track's forward direction and a lever of 1. None when it asks nothing (on the centre,
    or where the track pushes straight towards or away from it)."""
    rates, levers = _asks(np.array([point], dtype=float), normal, track_y, speed_m_s, center)
    return (float(rates[0]), float(levers[0])) if len(rates) else None


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
) -> np.ndarray:
    """Rows (asked rate, load, lever) for the patch's points (`asked_rate`), the load shared evenly between them;
    `frame` is the track plane's origin and its x, y, z axes in the world."""
    origin, *axes = (np.asarray(v, dtype=float) for v in frame)
    points = origin + np.asarray(patch.points_m, dtype=float).reshape(-1, 3) @ np.array(axes)
    rates, levers = _asks(points, patch.normal, frame[2], speed_m_s, center)
    share = patch.load_n / max(1, len(patch.points_m))
    return np.column_stack((rates, np.full(len(rates), share), levers))


def settled_rate(
    asks: np.ndarray | Iterable[tuple[float, float, float]], slip_m_s: float = SLIP_SPEED_M_S
) -> float | None:
    """The rate at which the asks' friction moments about the centre balance: each (rate, load, lever) pulls with
    load · lever · s, s the slip lever · (its rate − the rate) over `slip_m_s`, clipped to ±1. None for no asks;
    with no load at all, the middle of the asked rates."""
    items = np.asarray(asks if isinstance(asks, np.ndarray) else list(asks), dtype=float).reshape(-1, 3)
    if not len(items):
        return None
    rates, loads, levers = items.T
    if loads.sum() <= 0.0:
        return (float(rates.min()) + float(rates.max())) / 2.0
    moment, reach = loads * levers, slip_m_s / levers
    # the pull falls as the rate rises, linearly between the rates where some contact starts or stops slipping
    # fully: evaluated there, it is zero where two neighbours' pulls change sign, or over a span (opposite
    # pulls both saturated), any rate in which balances: the middle of it
    knots = np.sort(np.concatenate((rates - reach, rates + reach)))
    pulls = (moment * np.clip((rates - knots[:, None]) / reach, -1.0, 1.0)).sum(axis=1)

    def crossing(k: int) -> float:  # the zero of the segment knots[k - 1], knots[k]
        p0, p1 = pulls[k - 1], pulls[k]
        # the fraction first: pulls of a subnormal load times the span underflow to 0 (5e-324 · 0.04 = 0)
        return float(knots[k - 1] + (knots[k] - knots[k - 1]) * (p0 / (p0 - p1))) if p0 != p1 else float(knots[k])

    # (the lowest knot pulls up, the highest down: both indices exist; a pull within rounding of 0 is 0)
    rounding = 1e-9 * float(moment.sum())
    last_up = int(np.argmax(pulls <= rounding))  # the first knot no longer pulling up
    first_down = int(np.argmax(pulls < -rounding))  # the first knot pulling down
    return (crossing(last_up) + crossing(first_down)) / 2.0


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
