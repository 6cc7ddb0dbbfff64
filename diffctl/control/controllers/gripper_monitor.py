"""When a gripper goal is done (the gripper controllers of ros2_controllers, Jazzy): reached once the position
error is below `goal_tolerance`; stalled once the gripper has not moved faster than `stall_velocity_threshold` for
more than `stall_timeout` seconds (a success with `allow_stalling`, else an abort)."""

from __future__ import annotations

from dataclasses import dataclass

REACHED, STALLED = "reached", "stalled"


@dataclass
class StallMonitor:
    goal_tolerance: float
    stall_velocity_threshold: float
    stall_timeout_s: float
    last_movement_ns: int = 0

    def start(self, time_ns: int) -> None:
        self.last_movement_ns = time_ns

    def check(self, time_ns: int, position_error: float, velocity: float) -> str | None:
        if abs(position_error) < self.goal_tolerance:
            return REACHED
        if abs(velocity) > self.stall_velocity_threshold:
            self.last_movement_ns = time_ns
        elif (time_ns - self.last_movement_ns) * 1e-9 > self.stall_timeout_s:
            return STALLED
        return None
