"""Path and goal tolerances of joint_trajectory_controller (its tolerances.hpp, Jazzy tip).

Defaults come from the parameters (`constraints.<joint>.trajectory` / `.goal`, `constraints.goal_time`,
`constraints.stopped_velocity_tolerance`); an action goal may override them per joint with control_msgs'
JointTolerance convention: a positive value replaces the default, 0 keeps it, -1 erases it (no limit), and any
other negative value is illegal — the whole goal's tolerances then fall back to the defaults, with an error.
A tolerance of 0 means "not checked".
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace

_FLOAT_EPS = 1.1920928955078125e-07  # the reference compares -1 within float's epsilon


@dataclass(frozen=True)
class StateTolerance:
    position: float = 0.0
    velocity: float = 0.0
    acceleration: float = 0.0


@dataclass(frozen=True)
class SegmentTolerances:
    state: tuple[StateTolerance, ...] = ()  # while moving, per joint
    goal_state: tuple[StateTolerance, ...] = ()  # at the end, per joint
    goal_time_s: float = 0.0  # 0: wait for the goal state as long as it takes


@dataclass(frozen=True)
class JointToleranceRequest:
    """One control_msgs/JointTolerance of a goal."""

    name: str
    position: float = 0.0
    velocity: float = 0.0
    acceleration: float = 0.0


def from_parameters(joints: Sequence[str], trajectory: Sequence[float], goal: Sequence[float],
                    stopped_velocity: float, goal_time_s: float) -> SegmentTolerances:
    """The default tolerances: per joint a path position tolerance, a goal position tolerance and the stopped
    velocity as goal velocity tolerance."""
    return SegmentTolerances(
        tuple(StateTolerance(position=trajectory[i]) for i in range(len(joints))),
        tuple(StateTolerance(position=goal[i], velocity=stopped_velocity) for i in range(len(joints))),
        goal_time_s,
    )


class IllegalTolerance(ValueError):
    pass


def resolve(default: float, requested: float) -> float:
    """The tolerance a goal's value asks for (see the module docstring)."""
    if requested > 0.0:
        return requested
    if abs(requested + 1.0) < _FLOAT_EPS:
        return 0.0
    if requested < 0.0:
        raise IllegalTolerance(requested)
    return default


@dataclass
class GoalTolerances:
    """What a goal asks: its goal_time_tolerance and its path/goal JointTolerance entries."""

    goal_time_s: float = 0.0
    path: list[JointToleranceRequest] = field(default_factory=list)
    goal: list[JointToleranceRequest] = field(default_factory=list)


def for_goal(defaults: SegmentTolerances, request: GoalTolerances, joints: Sequence[str],
             errors: list[str] | None = None) -> SegmentTolerances:
    """`defaults` with the goal's overrides; the defaults unchanged (and the reason appended to `errors`) when
    the goal names an unknown joint or gives an illegal value."""
    errors = errors if errors is not None else []
    try:
        goal_time_s = resolve(defaults.goal_time_s, request.goal_time_s)
    except IllegalTolerance:
        errors.append(f"Specified illegal goal_time_tolerance: {request.goal_time_s:f}. Using default tolerances")
        return defaults
    tables = {"path_tolerance": list(defaults.state), "goal_tolerance": list(defaults.goal_state)}
    for kind, entries in (("path_tolerance", request.path), ("goal_tolerance", request.goal)):
        table = tables[kind]
        for entry in entries:
            if entry.name not in joints:
                errors.append(f"joint '{entry.name}' specified in goal.{kind} does not exist. "
                              "Using default tolerances.")
                return defaults
            i = list(joints).index(entry.name)
            base = table[i]
            values = {}
            for component in ("position", "velocity", "acceleration"):
                try:
                    values[component] = resolve(getattr(base, component), getattr(entry, component))
                except IllegalTolerance:
                    errors.append(f"joint '{entry.name}' specified in goal.{kind} has a invalid {component} "
                                  "tolerance. Using default tolerances.")
                    return defaults
            table[i] = replace(base, **values)
    return SegmentTolerances(tuple(tables["path_tolerance"]), tuple(tables["goal_tolerance"]), goal_time_s)


def violations(tolerance: StateTolerance, position_error: float, velocity_error: float = 0.0,
               acceleration_error: float = 0.0) -> list[str]:
    """The components of one joint's error outside its (non-zero) tolerance, as the reference reports them;
    empty when the error is within tolerance (a NaN error passes, as in the reference)."""
    out = []
    for name, tol, err in (("Position", tolerance.position, position_error),
                           ("Velocity", tolerance.velocity, velocity_error),
                           ("Acceleration", tolerance.acceleration, acceleration_error)):
        if tol > 0.0 and abs(err) > tol:
            out.append(f"{name} Error: {err:f}, {name} Tolerance: {tol:f}")
    return out


def within(tolerance: StateTolerance, position_error: float, velocity_error: float = 0.0,
           acceleration_error: float = 0.0) -> bool:
    return not (
        (tolerance.position > 0.0 and abs(position_error) > tolerance.position)
        or (tolerance.velocity > 0.0 and abs(velocity_error) > tolerance.velocity)
        or (tolerance.acceleration > 0.0 and abs(acceleration_error) > tolerance.acceleration)
    )
