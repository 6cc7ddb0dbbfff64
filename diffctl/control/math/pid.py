"""control_toolbox's Pid (Jazzy): P, I and D on an error and its derivative, with output clamping and the
anti-windup strategies of its AntiWindupStrategy.

The strategies, by name:
  legacy                   the integral accumulates every step and is clamped to [i_min, i_max] only where it
                           enters the output (or on accumulation when `legacy_antiwindup`), then at the end
  none                     plain accumulation, clamped to [i_min, i_max]
  back_calculation         the integral is pulled back by (saturated − unsaturated) / tracking_time_constant
                           (0 picks √(d/i), or p/i without d)
  conditional_integration  no accumulation while the output saturates in the error's direction
Errors within `error_deadband` of zero do not integrate. A non-finite error makes the command NaN.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

STRATEGIES = ("back_calculation", "conditional_integration", "legacy", "none")
_EPS = 2.220446049250313e-16


@dataclass(frozen=True)
class PidGains:
    p: float = 0.0
    i: float = 0.0
    d: float = 0.0
    u_max: float = math.inf
    u_min: float = -math.inf
    antiwindup_strategy: str = "legacy"
    i_max: float = math.inf
    i_min: float = -math.inf
    legacy_antiwindup: bool = False
    tracking_time_constant: float = 0.0
    error_deadband: float = _EPS

    def problem(self) -> str | None:
        """Why control_toolbox would refuse these gains, or None."""
        if not self.u_min < self.u_max:
            if math.isnan(self.u_min) or math.isnan(self.u_max):
                return "Gains: u_min and u_max must not be NaN"
            return f"Gains: u_min ({self.u_min:g}) must be less than u_max ({self.u_max:g})"
        if self.antiwindup_strategy not in STRATEGIES:
            return (f"AntiWindupStrategy: Unknown antiwindup strategy : '{self.antiwindup_strategy}'. Valid "
                    "strategies are: 'back_calculation', 'conditional_integration', 'legacy', 'none'.")
        tc = self.tracking_time_constant
        if self.antiwindup_strategy == "back_calculation" and (tc < 0.0 or not math.isfinite(tc)):
            return ("AntiWindupStrategy 'back_calculation' requires a valid positive tracking time constant "
                    "(tracking_time_constant)")
        if self.i_min > 0:
            return f"PID requires i_min to be smaller or equal to 0 (i_min: {self.i_min:g})"
        if self.i_max < 0:
            return f"PID requires i_max to be greater or equal to 0 (i_max: {self.i_max:g})"
        return None

    def effective(self) -> PidGains:
        """The gains as control_toolbox keeps them: back_calculation's zero time constant replaced."""
        if self.antiwindup_strategy == "back_calculation" and abs(self.tracking_time_constant) <= _EPS \
                and abs(self.i) > _EPS:
            tc = math.sqrt(self.d / self.i) if abs(self.d) > _EPS else self.p / self.i
            return replace(self, tracking_time_constant=tc)
        return self


class Pid:
    """One PID loop; `compute_command(error, error_dot, dt_s)` (or without error_dot: it is differenced)."""

    def __init__(self, gains: PidGains | None = None) -> None:
        self.gains = PidGains()
        if gains is not None and not self.set_gains(gains):
            raise ValueError(gains.problem())
        self.reset()

    def set_gains(self, gains: PidGains) -> bool:
        """Take `gains` unless control_toolbox would refuse them (then False, the old gains stay)."""
        if gains.problem() is not None:
            return False
        self.gains = gains.effective()
        return True

    def reset(self, keep_integral: bool = False) -> None:
        self.p_error_last = 0.0
        self.p_error = 0.0
        self.d_error = 0.0
        self.command = 0.0
        if not keep_integral:
            self.i_term = 0.0

    def compute_command(self, error: float, error_dot: float | None, dt_s: float) -> float:
        if abs(dt_s) <= _EPS:
            return self.command
        if dt_s < 0.0:
            raise ValueError("Pid is called with negative dt")
        if error_dot is None:
            if not math.isfinite(error):
                self.command = math.nan
                return self.command
            error_dot = (error - self.p_error_last) / dt_s
            self.p_error_last = error
        g = self.gains
        self.p_error, self.d_error = error, error_dot
        if not (math.isfinite(error) and math.isfinite(error_dot)):
            self.command = math.nan
            return self.command
        integrating = abs(error) > g.error_deadband
        strategy = g.antiwindup_strategy
        if strategy == "legacy" and integrating:
            self.i_term += g.i * dt_s * error
            if g.legacy_antiwindup:
                self.i_term = min(max(self.i_term, g.i_min), g.i_max)
        i_part = self.i_term
        if strategy == "legacy" and not g.legacy_antiwindup:
            i_part = min(max(i_part, g.i_min), g.i_max)
        unsaturated = g.p * error + i_part + g.d * error_dot
        command = unsaturated
        if math.isfinite(g.u_min) or math.isfinite(g.u_max):
            command = min(max(unsaturated, g.u_min), g.u_max)
        if integrating:
            if strategy == "back_calculation" and abs(g.i) > _EPS:
                self.i_term += dt_s * (g.i * error + (command - unsaturated) / g.tracking_time_constant)
            elif strategy == "conditional_integration":
                saturating_along = abs(unsaturated - command) > _EPS and error * unsaturated > 0
                if not saturating_along:
                    self.i_term += dt_s * g.i * error
            elif strategy == "none":
                self.i_term += dt_s * g.i * error
        self.i_term = min(max(self.i_term, g.i_min), g.i_max)
        self.command = command
        return command
