"""How often a camera may render: Gazebo's requested rate, lowered when the CPU cannot keep up (pure logic).

A frame rendered on the CPU takes wall time that the simulation spends not stepping. At real-time factor r a
render period of p seconds of sim time lasts p / r seconds of wall time; a camera may spend at most
RENDER_BUDGET of that rendering. When its measured render time would exceed that, its period grows (on the
physics step grid) to what fits. It only grows: a rate that could not be kept once is not retried, so the
images keep one steady rate and the warning is said once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

# Share of wall time one camera may spend rendering (the rest is for physics, control and other sensors).
RENDER_BUDGET = 0.5
# Frames measured before a decision: the first one carries one-off costs (shading the ground's colour).
WARMUP_FRAMES = 2
SMOOTHING = 0.3
# Lower only when the rate would change by more than this factor, so noise in timing does not nudge it.
HYSTERESIS = 1.1


@dataclass
class RenderRate:
    requested_period_ns: int
    step_ns: int
    budget: float = RENDER_BUDGET
    period_ns: int = field(init=False)
    _frames: int = field(default=0, init=False)
    _mean_s: float = field(default=0.0, init=False)

    def __post_init__(self) -> None:
        self.period_ns = self.requested_period_ns

    def observe(self, render_wall_s: float, rtf: float) -> int | None:
        """Record one frame's render time at real-time factor `rtf` (≤ 0: as fast as possible, no wall-time
        target to keep); the new, longer period when the current one cannot be kept, else None."""
        self._frames += 1
        if self._frames == 1:
            return None
        self._mean_s = (
            render_wall_s if self._frames == 2 else SMOOTHING * render_wall_s + (1 - SMOOTHING) * self._mean_s
        )
        if self._frames <= WARMUP_FRAMES or rtf <= 0:
            return None
        needed_ns = self._mean_s * rtf / self.budget * 1e9
        if needed_ns <= self.period_ns * HYSTERESIS:
            return None
        self.period_ns = max(self.period_ns, math.ceil(needed_ns / self.step_ns) * self.step_ns)
        return self.period_ns

    @property
    def lowered(self) -> bool:
        return self.period_ns > self.requested_period_ns
