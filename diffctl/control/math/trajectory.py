"""Joint trajectories as joint_trajectory_controller samples them (Jazzy tip): splines between waypoints.

A `TrajectoryPoint` holds per-joint lists (an empty list: "not given") and its `time_from_start_ns`. Between two
points the degree of the spline follows what both ends give: positions only → linear, with velocities →
cubic, with velocities and accelerations → quintic; effort is always linear. A point that gives no position
(a velocity- or acceleration-only waypoint) gets one integrated from its neighbour first, with the trapezoid
rule, as the reference does. Joints that wrap around (continuous joints) start from the representation of the
current angle nearest the first waypoint, so they take the short way.

`Trajectory.sample(t_ns)` gives the desired state at a time and which segment it falls in. Times are ROS
times in integer nanoseconds; a trajectory whose start is 0 starts at its first sample.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

_TWO_PI = 2.0 * math.pi
_NS = 1e-9


@dataclass
class TrajectoryPoint:
    positions: list[float] = field(default_factory=list)
    velocities: list[float] = field(default_factory=list)
    accelerations: list[float] = field(default_factory=list)
    effort: list[float] = field(default_factory=list)
    time_from_start_ns: int = 0

    def copy(self) -> TrajectoryPoint:
        return TrajectoryPoint(list(self.positions), list(self.velocities), list(self.accelerations),
                               list(self.effort), self.time_from_start_ns)


def shortest_angular_distance(from_rad: float, to_rad: float) -> float:
    """The signed angle in [-π, π] that turns `from_rad` into `to_rad` (angles' shortest_angular_distance)."""
    d = math.fmod(to_rad - from_rad, _TWO_PI)
    d = math.fmod(d + _TWO_PI, _TWO_PI)  # into [0, 2π)
    return d - _TWO_PI if d > math.pi else d


def unwrap_towards(current_rad: list[float], target_rad: list[float], wraps: list[bool]) -> None:
    """Shift each wrapping joint of `current_rad` (in place) by whole turns so it lies within half a turn of its
    target; exactly half a turn away, it moves in the direction of the target's larger value."""
    for i, wrapping in enumerate(wraps):
        if not wrapping or i >= len(target_rad):
            continue
        gap = shortest_angular_distance(current_rad[i], target_rad[i])
        if abs(abs(gap) - math.pi) < 1e-9:
            gap = abs(gap) if target_rad[i] > current_rad[i] else -abs(gap)
        current_rad[i] = target_rad[i] - gap


def _coefficients(duration_s: float, p0: float, p1: float, v: tuple[float, float] | None,
                  a: tuple[float, float] | None) -> tuple[float, ...]:
    """Polynomial coefficients (lowest order first) of the segment from (p0, v0, a0) to (p1, v1, a1) over
    `duration_s`; a zero-length segment stays at its start."""
    if v is None:
        slope = (p1 - p0) / duration_s if duration_s != 0.0 else 0.0
        return (p0, slope)
    v0, v1 = v
    if a is None:
        if duration_s == 0.0:
            return (p0, v0, 0.0, 0.0)
        rise, T = p1 - p0, duration_s
        return (p0, v0, (3.0 * rise - (2.0 * v0 + v1) * T) / T**2, ((v0 + v1) * T - 2.0 * rise) / T**3)
    a0, a1 = a
    if duration_s == 0.0:
        return (p0, v0, 0.5 * a0, 0.0, 0.0, 0.0)
    rise, T = p1 - p0, duration_s
    T2 = T * T
    return (
        p0, v0, 0.5 * a0,
        (20.0 * rise - (12.0 * v0 + 8.0 * v1) * T - (3.0 * a0 - a1) * T2) / (2.0 * T**3),
        ((16.0 * v0 + 14.0 * v1) * T + (3.0 * a0 - 2.0 * a1) * T2 - 30.0 * rise) / (2.0 * T**4),
        (12.0 * rise - 6.0 * (v0 + v1) * T + (a1 - a0) * T2) / (2.0 * T**5),
    )  # fmt: skip


def _evaluate(c: tuple[float, ...], t: float) -> tuple[float, float, float]:
    """(value, first derivative, second derivative) of the polynomial `c` at `t`."""
    value = slope = curvature = 0.0
    for k in range(len(c) - 1, -1, -1):  # Horner, carrying the derivatives along
        curvature = curvature * t + 2.0 * slope
        slope = slope * t + value
        value = value * t + c[k]
    return value, slope, curvature


def interpolate(t_a_ns: int, a: TrajectoryPoint, t_b_ns: int, b: TrajectoryPoint, t_ns: int) -> TrajectoryPoint:
    """The state at `t_ns` on the spline from `a` (at `t_a_ns`) to `b` (at `t_b_ns`). Outside the segment the
    nearer end's position is held with the linear slope (derivatives beyond the ends are not extrapolated)."""
    span_s = (t_b_ns - t_a_ns) * _NS
    elapsed_ns = t_ns - t_a_ns
    use_vel = bool(a.velocities) and bool(b.velocities)
    use_acc = bool(a.accelerations) and bool(b.accelerations)
    if elapsed_ns < 0:
        elapsed_ns, use_vel, use_acc = 0, False, False
    elif elapsed_ns > t_b_ns - t_a_ns:
        elapsed_ns, use_vel, use_acc = t_b_ns - t_a_ns, False, False
    t = elapsed_ns * _NS
    n = len(a.positions)
    out = TrajectoryPoint([0.0] * n, [0.0] * n, [0.0] * n, [0.0] * n)
    if a.effort and b.effort:
        for i in range(n):
            out.effort[i] = _evaluate(_coefficients(span_s, a.effort[i], b.effort[i], None, None), t)[0]
    if not use_vel and use_acc:
        return out  # accelerations without velocities: the reference leaves the state at zero
    for i in range(n):
        v = (a.velocities[i], b.velocities[i]) if use_vel else None
        acc = (a.accelerations[i], b.accelerations[i]) if use_acc else None
        c = _coefficients(span_s, a.positions[i], b.positions[i], v, acc)
        out.positions[i], out.velocities[i], curvature = _evaluate(c, t)
        if v is not None:
            out.accelerations[i] = curvature
    return out


def integrate_missing(first: TrajectoryPoint, second: TrajectoryPoint, n_joints: int, duration_s: float) -> None:
    """Give `second` the positions (and velocities) it lacks from `first` over `duration_s` by the trapezoid
    rule, missing derivatives of `first` counting as zero; both get zero effort when they have none."""
    if not first.effort:
        first.effort = [0.0] * n_joints
    if not second.effort:
        second.effort = [0.0] * n_joints
    if second.positions:
        return
    if not first.velocities:
        first.velocities = [0.0] * n_joints
    if not second.velocities:
        if not first.accelerations:
            first.accelerations = [0.0] * n_joints
        second.velocities = [first.velocities[i] + 0.5 * duration_s * (first.accelerations[i]
                             + second.accelerations[i]) for i in range(n_joints)]
    second.positions = [first.positions[i] + 0.5 * duration_s * (first.velocities[i] + second.velocities[i])
                        for i in range(n_joints)]


@dataclass
class Sample:
    """A sampled state and the segment it came from: `start`/`end` index the waypoints, `end == len(points)`
    once the last waypoint's time has passed; both 0 before the first waypoint."""

    point: TrajectoryPoint
    start: int
    end: int


class Trajectory:
    """One received trajectory: its waypoints (already in the controller's joint order), its start time, and
    the state it starts from (set at its first sample)."""

    def __init__(self, points: list[TrajectoryPoint] | None = None, start_time_ns: int = 0) -> None:
        self.points: list[TrajectoryPoint] | None = points
        self.start_time_ns = start_time_ns
        self.sampled_already = False
        self.last_sample_index = 0
        self.time_before_ns = 0
        self.state_before = TrajectoryPoint()

    def replace(self, points: list[TrajectoryPoint], start_time_ns: int) -> None:
        """Take a new trajectory; the state before it is set again at its first sample."""
        self.points = points
        self.start_time_ns = start_time_ns
        self.sampled_already = False
        self.last_sample_index = 0

    def has_points(self) -> bool:
        return self.points is not None

    def set_state_before(self, time_ns: int, state: TrajectoryPoint, wraps: list[bool]) -> None:
        """Where the trajectory starts from: `state` at `time_ns`, given the derivatives the first waypoint
        has (as zeros) so the first segment is a spline of the same degree, and unwrapped towards it."""
        assert self.points is not None
        first = self.points[0]
        before = state.copy()
        if not before.velocities and first.velocities:
            before.velocities = [0.0] * len(first.velocities)
        if not before.accelerations and first.accelerations:
            before.accelerations = [0.0] * len(first.accelerations)
        unwrap_towards(before.positions, first.positions, wraps)
        self.time_before_ns = time_ns
        self.state_before = before

    def sample(self, t_ns: int, interpolate_splines: bool = True, advance: bool = True) -> Sample | None:
        """The desired state at `t_ns`, or None before the state it starts from (or when nothing can be
        sampled). `advance` lets later samples skip the segments already passed."""
        points = self.points
        assert points is not None
        if not points:
            return None
        if not self.sampled_already:
            if self.start_time_ns == 0:
                self.start_time_ns = t_ns
            self.sampled_already = True
        if t_ns < self.time_before_ns:
            return None
        start_ns = self.start_time_ns
        n_joints = len(self.state_before.positions)
        first_ns = start_ns + points[0].time_from_start_ns
        if t_ns < first_ns:
            if interpolate_splines:
                integrate_missing(self.state_before, points[0], n_joints, (first_ns - self.time_before_ns) * _NS)
                state = interpolate(self.time_before_ns, self.state_before, first_ns, points[0], t_ns)
            else:
                state = self.state_before.copy()
            return Sample(state, 0, 0)
        last = len(points) - 1
        for i in range(self.last_sample_index, last):
            t0 = start_ns + points[i].time_from_start_ns
            t1 = start_ns + points[i + 1].time_from_start_ns
            if t0 <= t_ns < t1:
                if interpolate_splines:
                    integrate_missing(points[i], points[i + 1], n_joints, (t1 - t0) * _NS)
                    state = interpolate(t0, points[i], t1, points[i + 1], t_ns)
                else:
                    state = points[i + 1].copy()
                state.time_from_start_ns = points[i + 1].time_from_start_ns
                if advance:
                    self.last_sample_index = i
                return Sample(state, i, i + 1)
        self.last_sample_index = last
        if not points[last].positions and last > 0 and points[last - 1].positions:
            # the last segment was stepped over (the controller's period is longer than it): integrate it now
            t_prev = start_ns + points[last - 1].time_from_start_ns
            integrate_missing(points[last - 1], points[last], n_joints,
                              (start_ns + points[last].time_from_start_ns - t_prev) * _NS)
        state = points[last].copy()
        if not state.positions:
            return None
        n = len(state.positions)
        for name in ("velocities", "accelerations", "effort"):
            if not getattr(state, name):
                setattr(state, name, [0.0] * n)
        return Sample(state, last, last + 1)


def decelerating_stop(positions: list[float], velocities_rps: list[float], max_deceleration: list[float],
                      step_s: float, min_points: int = 1) -> list[TrajectoryPoint]:
    """Waypoints every `step_s` that brake each joint from its velocity at constant `max_deceleration` (> 0) to
    rest, then hold where it stopped (decelerate_on_cancel); at least `min_points` waypoints."""
    n = len(positions)
    stop_s = [abs(velocities_rps[i]) / max_deceleration[i] for i in range(n)]
    count = max(min_points, math.ceil(max(stop_s, default=0.0) / step_s) + 1)
    rest = [positions[i] + math.copysign(velocities_rps[i] ** 2 / (2.0 * max_deceleration[i]),
                                         1.0 if velocities_rps[i] >= 0.0 else -1.0) for i in range(n)]
    out = []
    for k in range(count):
        t = k * step_s
        point = TrajectoryPoint([0.0] * n, [0.0] * n, [0.0] * n, [], round(t * 1e9))
        for i in range(n):
            v0 = velocities_rps[i]
            if t < stop_s[i] and abs(v0) > 1.1920928955078125e-07:
                brake = max_deceleration[i] if v0 >= 0.0 else -max_deceleration[i]
                v = v0 - brake * t
                point.velocities[i] = 0.0 if v * (1.0 if v0 >= 0.0 else -1.0) < 0.0 else v
                point.positions[i] = positions[i] + v0 * t - 0.5 * brake * t * t
                point.accelerations[i] = -brake
            else:
                point.positions[i] = rest[i]
        out.append(point)
    return out
