"""The measurement queue around a filter, as robot_localization's nodes run it each cycle.

Measurements wait in time order and are fused when the node's clock reaches them; without new ones the
state is predicted on after sensor_timeout (or every cycle with predict_to_current_time). With
smooth_lagged_data a late measurement rolls the filter back to the last state before it and replays the
measurements since, from up to history_length of saved states.
"""

from __future__ import annotations

import heapq
import itertools
from collections import deque
from dataclasses import dataclass

import numpy as np

from diffctl.robot_localization.filter_base import FilterBase, Measurement
from diffctl.robot_localization.state import STATE_SIZE, VROLL


@dataclass(frozen=True)
class SavedState:
    state: np.ndarray
    covariance: np.ndarray
    last_measurement_ns: int
    latest_control: np.ndarray
    latest_control_ns: int


class Estimator:
    def __init__(self, filt: FilterBase, *, smooth_lagged_data: bool = False, history_length_ns: int = 0,
                 predict_to_current_time: bool = False) -> None:
        self.filter = filt
        self.smooth_lagged_data = smooth_lagged_data
        self.history_length_ns = history_length_ns
        self.predict_to_current_time = predict_to_current_time
        self._queue: list[tuple[int, int, Measurement]] = []
        self._order = itertools.count()
        self.measurement_history: deque[Measurement] = deque()
        self.state_history: deque[SavedState] = deque()
        self.angular_acceleration = np.zeros(3)
        self.angular_acceleration_covariance = np.zeros((3, 3))
        self._last_rates = np.zeros(3)
        self._last_diff_s = 0.0

    def enqueue(self, m: Measurement) -> None:
        heapq.heappush(self._queue, (m.time_ns, next(self._order), m))

    def clear_queue(self) -> None:
        self._queue.clear()

    def clear_history(self) -> None:
        self.measurement_history.clear()
        self.state_history.clear()

    def queued(self) -> int:
        return len(self._queue)

    def _save(self) -> None:
        f = self.filter
        self.state_history.append(SavedState(f.state.copy(), f.covariance.copy(), f.last_measurement_ns,
                                             f.latest_control.copy(), f.latest_control_ns))

    def _revert_to(self, time_ns: int) -> bool:
        """Back to the newest saved state at or before `time_ns`, its later measurements queued again. False
        when the history does not reach that far (the oldest state it has is used then)."""
        last: SavedState | None = None
        while self.state_history and self.state_history[-1].last_measurement_ns > time_ns:
            last = self.state_history.pop()
        reached = bool(self.state_history)
        if reached:
            last = self.state_history[-1]
        if last is not None:
            f = self.filter
            f.state = last.state.copy()
            f.covariance = last.covariance.copy()
            f.last_measurement_ns = last.last_measurement_ns
            while self.measurement_history and self.measurement_history[-1].time_ns > time_ns:
                m = self.measurement_history.pop()
                if last.last_measurement_ns <= m.time_ns:
                    self.enqueue(m)
        return reached

    def integrate(self, now_ns: int) -> None:
        """Fuse every queued measurement up to `now_ns`; predict on when they stopped coming."""
        f = self.filter
        predict_now = self.predict_to_current_time
        if self._queue:
            restored = 0
            if self.smooth_lagged_data and self._queue[0][0] < f.last_measurement_ns:
                before = len(self._queue)
                self._revert_to(self._queue[0][0] - 1)
                restored = len(self._queue) - before
            while self._queue and self._queue[0][0] <= now_ns:
                _, _, m = heapq.heappop(self._queue)
                # Replayed measurements carry the control that was current when they first came.
                if f.control is not None and restored > 0:
                    f.set_control(m.latest_control, m.latest_control_ns)
                    restored -= 1
                f.process(m)
                if self.smooth_lagged_data:
                    self.measurement_history.append(m)
                    if not self._queue or self._queue[0][0] != f.last_measurement_ns:
                        self._save()
        elif f.initialized and now_ns - f.last_measurement_ns >= f.sensor_timeout_ns:
            predict_now = True
        if f.initialized and predict_now:
            delta_ns = now_ns - f.last_measurement_ns
            f.predict(now_ns, delta_ns * 1e-9)
            f.last_measurement_ns += delta_ns

    def differentiate(self, now_ns: int) -> None:
        """Angular acceleration from the change of the estimated body rates since the last cycle."""
        f = self.filter
        if not f.initialized:
            return
        now_s = now_ns * 1e-9
        dt = now_s - self._last_diff_s
        rates = f.state[VROLL:VROLL + 3].copy()
        if dt != 0.0:
            self.angular_acceleration = (rates - self._last_rates) / dt
            self.angular_acceleration_covariance = f.covariance[VROLL:VROLL + 3, VROLL:VROLL + 3] * 2.0 / (dt * dt)
        self._last_rates = rates
        self._last_diff_s = now_s

    def clear_expired_history(self, cutoff_ns: int) -> None:
        while self.measurement_history and self.measurement_history[0].time_ns < cutoff_ns:
            self.measurement_history.popleft()
        while self.state_history and self.state_history[0].last_measurement_ns < cutoff_ns:
            self.state_history.popleft()

    def set_state(self, state: np.ndarray, covariance: np.ndarray, now_ns: int) -> None:
        """set_pose: the state and covariance as given, measured now."""
        f = self.filter
        f.state = np.array(state, dtype=float).reshape(STATE_SIZE)
        f.covariance = np.array(covariance, dtype=float).reshape(STATE_SIZE, STATE_SIZE)
        f.last_measurement_ns = now_ns
