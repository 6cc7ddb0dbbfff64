"""Soft limits (URDF `<safety_controller>`) on top of the hard ones (joint_limits/JointInterfacesSoftLimiter).

Inside [soft_lower_limit, soft_upper_limit] the joint may move at up to max_velocity; towards a soft bound its
speed is ramped down as k_position × (distance to that bound), beyond a soft bound it may creep back at 1°/s
(or that many m/s), and past a hard bound (by the tolerance) it may not move. Position commands stay inside the
soft range and within a period's reach of the previous command at those speeds; an effort command gets
k_velocity × (speed bound − measured velocity), within ±max_effort.
"""

from __future__ import annotations

import math

from diffctl.control.joint_limits.joint_limits import JointControlInterfacesData, SoftJointLimits
from diffctl.control.joint_limits.joint_limits_helpers import (
    POSITION_BOUNDS_TOLERANCE,
    cclamp,
    cmax,
    cmin,
    compute_effort_limits,
    compute_position_limits,
    compute_velocity_limits,
    is_limited,
)
from diffctl.control.joint_limits.joint_saturation_limiter import JointSaturationLimiter, _given

VALUE_CONSIDERED_ZERO = 1e-10
SOFT_LIMIT_REACH_VELOCITY = math.radians(1.0)  # per second, back towards the soft range from outside it
_INF = math.inf


def has_soft_position_limits(soft: SoftJointLimits) -> bool:
    return (
        math.isfinite(soft.min_position)
        and math.isfinite(soft.max_position)
        and soft.max_position - soft.min_position > VALUE_CONSIDERED_ZERO
    )


def has_soft_limits(soft: SoftJointLimits) -> bool:
    return (
        has_soft_position_limits(soft)
        and math.isfinite(soft.k_position)
        and abs(soft.k_position) > VALUE_CONSIDERED_ZERO
    )


def _finite(value: float | None) -> bool:
    return value is not None and math.isfinite(value)


class JointSoftLimiter(JointSaturationLimiter):
    def _enforce(self, actual: JointControlInterfacesData, desired: JointControlInterfacesData, dt_s: float) -> bool:
        hard, soft, name, limited = self.limits, self.soft_limits, self.joint_name, False
        prev = self.prev_command
        # Where the joint is, and where it was last sent; each stands in for the other when missing.
        position = actual.position if actual.position is not None else (
            prev.position if _finite(prev.position) else _INF)
        reference = prev.position if _finite(prev.position) else (
            actual.position if actual.position is not None else _INF)

        vel_lo, vel_hi = -_INF, _INF
        if hard.has_velocity_limits:
            vmax = hard.max_velocity
            vel_lo, vel_hi = -vmax, vmax
            if hard.has_position_limits and has_soft_limits(soft) and math.isfinite(reference):
                # the reference, not the measurement: the state lags, and would slow the joint well before the bound
                vel_lo = cclamp(-soft.k_position * (reference - soft.min_position), -vmax, vmax)
                vel_hi = cclamp(-soft.k_position * (reference - soft.max_position), -vmax, vmax)
                tol = POSITION_BOUNDS_TOLERANCE
                if math.isfinite(position) and (
                    position < hard.min_position - tol or position > hard.max_position + tol
                ):
                    vel_lo = vel_hi = 0.0
                elif position < soft.min_position or position > soft.max_position:
                    vel_lo = math.copysign(SOFT_LIMIT_REACH_VELOCITY, vel_lo)
                    vel_hi = math.copysign(SOFT_LIMIT_REACH_VELOCITY, vel_hi)

        pos = desired.position
        if _given(pos):
            hard_lo, hard_hi = compute_position_limits(name, hard, actual.velocity, actual.position, prev.position,
                                                       dt_s)
            lo, hi = (soft.min_position, soft.max_position) if has_soft_position_limits(soft) else (-_INF, _INF)
            if hard.has_velocity_limits and math.isfinite(reference):
                lo = cclamp(reference + vel_lo * dt_s, lo, hi)
                hi = cclamp(reference + vel_hi * dt_s, lo, hi)
            reach_lo, reach_hi = lo, hi
            lo, hi = cmax(lo, hard_lo), cmin(hi, hard_hi)
            if lo > hi:
                # The reachable range misses the hard range (the previous command far outside the soft range):
                # stay with what velocity allows.
                lo, hi = reach_lo, reach_hi
            limited = is_limited(pos, lo, hi)
            desired.position = cclamp(pos, lo, hi)

        vel = desired.velocity
        if _given(vel):
            hard_lo, hard_hi = compute_velocity_limits(name, hard, vel, actual.position, prev.velocity, dt_s)
            if hard.has_velocity_limits and hard.has_acceleration_limits and actual.velocity is not None:
                dv = hard.max_acceleration * dt_s
                vel_lo = cmax(actual.velocity - dv, vel_lo)
                vel_hi = cmin(actual.velocity + dv, vel_hi)
            vel_lo, vel_hi = cmax(vel_lo, hard_lo), cmin(vel_hi, hard_hi)
            limited = is_limited(vel, vel_lo, vel_hi) or limited
            desired.velocity = cclamp(vel, vel_lo, vel_hi)

        eff = desired.effort
        if _given(eff):
            hard_lo, hard_hi = compute_effort_limits(hard, actual.position, actual.velocity, dt_s)
            lo, hi = hard_lo, hard_hi
            if hard.has_effort_limits and math.isfinite(soft.k_velocity) and actual.velocity is not None:
                emax = hard.max_effort
                lo = cmax(cclamp(-soft.k_velocity * (actual.velocity - vel_lo), -emax, emax), hard_lo)
                hi = cmin(cclamp(-soft.k_velocity * (actual.velocity - vel_hi), -emax, emax), hard_hi)
            limited = is_limited(eff, lo, hi) or limited
            desired.effort = cclamp(eff, lo, hi)

        return self._clamp_acceleration_and_jerk(actual, desired) or limited
