"""What the EKF and the UKF share: the state and its covariance, the predict/correct cycle driven by
timestamped measurements, the control term and the Mahalanobis gate.

Times are integer nanoseconds of the node's clock; durations given to `predict` are seconds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from diffctl.robot_localization.state import ANGLES, STATE_SIZE, TWIST_SIZE, VX, default_process_noise, wrap_angle

INITIAL_COVARIANCE = 1e-9  # tiny: the first measurement of each variable is taken as it comes
DEFAULT_SENSOR_TIMEOUT_NS = 33_333_333


@dataclass
class Measurement:
    """One sensor reading in the filter's frames: the full state vector with the variables it measures."""

    topic: str
    time_ns: int
    values: np.ndarray  # (15,)
    covariance: np.ndarray  # (15, 15)
    update: list[bool]  # which variables this measurement updates
    mahalanobis_threshold: float = math.inf
    latest_control: np.ndarray = field(default_factory=lambda: np.zeros(TWIST_SIZE))
    latest_control_ns: int = 0


@dataclass
class ControlParams:
    """use_control's settings: which body velocities are commanded, and how fast the state may follow."""

    update: list[bool]
    timeout_ns: int
    acceleration_limits: list[float]
    acceleration_gains: list[float]
    deceleration_limits: list[float]
    deceleration_gains: list[float]


def control_acceleration(state: float, control: float, accel_limit: float, accel_gain: float,
                         decel_limit: float, decel_gain: float) -> float:
    """The acceleration that moves a velocity `state` toward its commanded `control`, within the limits."""
    error = control - state
    same_sign = abs(error) <= abs(control) + 0.01
    set_point = control if same_sign else 0.0
    decelerating = abs(set_point) < abs(state)
    limit, gain = (decel_limit, decel_gain) if decelerating else (accel_limit, accel_gain)
    return min(max(gain * error, -limit), limit)


def passes_mahalanobis(innovation: np.ndarray, inverse_innovation_covariance: np.ndarray, n_sigmas: float) -> bool:
    """Whether the innovation lies within `n_sigmas` of the prediction (inf: always)."""
    squared = float(innovation @ (inverse_innovation_covariance @ innovation))
    return not squared >= n_sigmas * n_sigmas


class FilterBase:
    """The state, its covariance and the measurement cycle; `predict` and `correct` are the subclass's."""

    def __init__(self) -> None:
        self.control: ControlParams | None = None
        self.latest_control = np.zeros(TWIST_SIZE)
        self.latest_control_ns = 0
        self.use_dynamic_process_noise = False
        self.reset()

    def reset(self) -> None:
        self.initialized = False
        self.state = np.zeros(STATE_SIZE)
        self.predicted_state = np.zeros(STATE_SIZE)
        self.control_acceleration = np.zeros(TWIST_SIZE)
        self.covariance = np.eye(STATE_SIZE) * INITIAL_COVARIANCE
        self.sensor_timeout_ns = DEFAULT_SENSOR_TIMEOUT_NS
        self.last_measurement_ns = 0
        self.set_process_noise(default_process_noise())

    def set_process_noise(self, q: np.ndarray) -> None:
        self.process_noise = np.array(q, dtype=float)
        self.dynamic_process_noise = self.process_noise.copy()

    def set_control(self, control: np.ndarray, time_ns: int) -> None:
        self.latest_control = np.array(control, dtype=float)
        self.latest_control_ns = time_ns

    def process_noise_for(self, state: np.ndarray) -> np.ndarray:
        """Q, scaled on its pose block by the speed when dynamic_process_noise_covariance is on."""
        if not self.use_dynamic_process_noise:
            return self.process_noise
        speed = float(np.linalg.norm(state[VX:VX + TWIST_SIZE]))
        q = self.dynamic_process_noise
        q[:TWIST_SIZE, :TWIST_SIZE] = self.process_noise[:TWIST_SIZE, :TWIST_SIZE] * (speed * speed)
        return q

    def prepare_control(self, reference_ns: int) -> None:
        self.control_acceleration[:] = 0.0
        c = self.control
        if c is None:
            return
        timed_out = reference_ns - self.latest_control_ns >= c.timeout_ns
        for i in range(TWIST_SIZE):
            if c.update[i]:
                self.control_acceleration[i] = control_acceleration(
                    self.state[VX + i], 0.0 if timed_out else self.latest_control[i], c.acceleration_limits[i],
                    c.acceleration_gains[i], c.deceleration_limits[i], c.deceleration_gains[i])

    def wrap_state_angles(self) -> None:
        for i in ANGLES:
            self.state[i] = wrap_angle(self.state[i])

    def process(self, m: Measurement) -> None:
        """Predict up to the measurement's time (when later than the last one) and correct with it; the first
        measurement initializes the variables it carries."""
        delta_ns = 0
        if self.initialized:
            delta_ns = m.time_ns - self.last_measurement_ns
            if delta_ns > 0:
                self.predict(m.time_ns, delta_ns * 1e-9)
                self.predicted_state = self.state.copy()
            self.correct(m)
        else:
            idx = [i for i, u in enumerate(m.update) if u]
            self.state[idx] = m.values[idx]
            self.covariance[np.ix_(idx, idx)] = m.covariance[np.ix_(idx, idx)]
            self.initialized = True
        if delta_ns >= 0:
            self.last_measurement_ns = m.time_ns

    def measured_indices(self, m: Measurement) -> list[int]:
        """The variables `m` updates whose values are finite (NaN and inf are skipped, not fused)."""
        return [i for i, u in enumerate(m.update) if u and math.isfinite(m.values[i])]

    @staticmethod
    def measurement_covariance(m: Measurement, idx: list[int]) -> np.ndarray:
        """R of the measured subset: negative variances taken as their magnitude, none below 1e-9 (a zero
        variance against a zero state variance would make the gain blow up)."""
        r = m.covariance[np.ix_(idx, idx)].copy()
        d = np.abs(np.diagonal(r))
        np.fill_diagonal(r, np.maximum(d, 1e-9))
        return r

    def predict(self, reference_ns: int, dt_s: float) -> None:
        raise NotImplementedError

    def correct(self, m: Measurement) -> None:
        raise NotImplementedError
