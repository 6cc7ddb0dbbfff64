"""Saturation of one joint's commands to its hard limits (joint_limits/JointInterfacesSaturationLimiter).

`enforce(actual, desired, dt_s)` clamps each command `desired` carries, in place, to the range
joint_limits_helpers computes from the limits, the measured `actual` state and the limiter's previous (limited)
command, and tells whether anything was clamped. A NaN command is no command: it passes through and is not
remembered. The previous command starts from the first measurement (or the first command when nothing is
measured) and is forgotten by `reset_internals`, as the resource manager does after every command-mode switch.
"""

from __future__ import annotations

import math

from diffctl.control.joint_limits.joint_limits import JointControlInterfacesData, JointLimits, SoftJointLimits
from diffctl.control.joint_limits.joint_limits_helpers import (
    cclamp,
    compute_acceleration_limits,
    compute_effort_limits,
    compute_position_limits,
    compute_velocity_limits,
    is_limited,
)

_KINDS = ("position", "velocity", "effort", "acceleration", "jerk")


def _given(value: float | None) -> bool:
    return value is not None and not math.isnan(value)


class JointSaturationLimiter:
    def __init__(self, joint_name: str, limits: JointLimits, soft_limits: SoftJointLimits | None = None) -> None:
        self.joint_name = joint_name
        self.limits = limits
        self.soft_limits = soft_limits if soft_limits is not None else SoftJointLimits()
        self.prev_command = JointControlInterfacesData(joint_name)

    def configure(self, current: JointControlInterfacesData) -> bool:
        self.prev_command = current.copy()
        return True

    def reset_internals(self) -> None:
        self.prev_command = JointControlInterfacesData(self.joint_name)

    def enforce(self, actual: JointControlInterfacesData, desired: JointControlInterfacesData, dt_s: float) -> bool:
        if dt_s <= 0.0:
            return False
        self._seed_previous(actual, desired)
        limited = self._enforce(actual, desired, dt_s)
        self._remember(desired)
        return limited

    # --- the two limiters share these ------------------------------------------------------------------------
    def _seed_previous(self, actual: JointControlInterfacesData, desired: JointControlInterfacesData) -> None:
        """Before any command: the previous command of each interface commanded now is what is measured on it,
        or, unmeasured, this first command itself."""
        prev = self.prev_command
        if prev.has_data():
            return
        for kind in _KINDS:
            want = getattr(desired, kind)
            if want is None:
                continue
            have = getattr(actual, kind)
            if have is not None:
                setattr(prev, kind, have)
            elif not math.isnan(want):
                setattr(prev, kind, want)
        if actual.has_data():
            prev.joint_name = actual.joint_name
        elif desired.has_data():
            prev.joint_name = desired.joint_name

    def _remember(self, desired: JointControlInterfacesData) -> None:
        prev = self.prev_command
        for kind in _KINDS:
            value = getattr(desired, kind)
            if _given(value):
                setattr(prev, kind, value)
        prev.joint_name = desired.joint_name

    def _clamp_acceleration_and_jerk(self, actual: JointControlInterfacesData,
                                     desired: JointControlInterfacesData) -> bool:
        limited = False
        acc = desired.acceleration
        if _given(acc):
            lo, hi = compute_acceleration_limits(self.limits, acc, actual.velocity)
            limited = is_limited(acc, lo, hi)
            desired.acceleration = cclamp(acc, lo, hi)
        jerk = desired.jerk
        if _given(jerk):
            # max_jerk alone decides (NaN when not set: nothing is clamped), as upstream does
            bound = self.limits.max_jerk
            limited = is_limited(jerk, -bound, bound) or limited
            desired.jerk = cclamp(jerk, -bound, bound)
        return limited

    # --- hard saturation -------------------------------------------------------------------------------------
    def _enforce(self, actual: JointControlInterfacesData, desired: JointControlInterfacesData, dt_s: float) -> bool:
        lim, name, limited = self.limits, self.joint_name, False
        pos = desired.position
        if _given(pos):
            lo, hi = compute_position_limits(name, lim, actual.velocity, actual.position, self.prev_command.position,
                                             dt_s)
            limited = is_limited(pos, lo, hi)
            desired.position = cclamp(pos, lo, hi)
        vel = desired.velocity
        if _given(vel):
            lo, hi = compute_velocity_limits(name, lim, vel, actual.position, self.prev_command.velocity, dt_s)
            limited = is_limited(vel, lo, hi) or limited
            desired.velocity = cclamp(vel, lo, hi)
        eff = desired.effort
        if _given(eff):
            lo, hi = compute_effort_limits(lim, actual.position, actual.velocity, dt_s)
            limited = is_limited(eff, lo, hi) or limited
            desired.effort = cclamp(eff, lo, hi)
        return self._clamp_acceleration_and_jerk(actual, desired) or limited
