"""gz-math's PID, as Gazebo's joint controller systems use it (pure math).

The command is offset − P·e − I − D·ė for the error e = state − target (note the signs: the error is measured
from the target, the command pushes back), the integral term I accumulates i_gain·dt·e and is clamped to
[i_min, i_max] when i_max >= i_min, the derivative is the error's change over dt, and the command is clamped
to [cmd_min, cmd_max] when cmd_max >= cmd_min. A zero dt or a non-finite error gives 0 and changes nothing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass
class GzPid:
    p_gain: float = 0.0
    i_gain: float = 0.0
    d_gain: float = 0.0
    i_max: float = -1.0
    i_min: float = 0.0
    cmd_max: float = -1.0
    cmd_min: float = 0.0
    cmd_offset: float = 0.0
    i_err: float = 0.0
    p_err_last: float = 0.0

    def update(self, error: float, dt_s: float) -> float:
        if dt_s == 0.0 or not math.isfinite(error):
            return 0.0
        rate = (error - self.p_err_last) / dt_s
        self.i_err += self.i_gain * dt_s * error
        if self.i_max >= self.i_min:
            self.i_err = min(max(self.i_err, self.i_min), self.i_max)
        self.p_err_last = error
        cmd = self.cmd_offset - self.p_gain * error - self.i_err - self.d_gain * rate
        if self.cmd_max >= self.cmd_min:
            cmd = min(max(cmd, self.cmd_min), self.cmd_max)
        return cmd

    def reset(self) -> None:
        self.i_err = 0.0
        self.p_err_last = 0.0
