"""The unscented Kalman filter of ukf_node: 2n+1 sigma points of the state through the motion model, angles
averaged on the circle, the measurement predicted from the sigma points."""

from __future__ import annotations

import numpy as np

from diffctl.robot_localization import motion_model
from diffctl.robot_localization.filter_base import FilterBase, Measurement, passes_mahalanobis
from diffctl.robot_localization.state import ANGLES, AX, STATE_SIZE, VROLL, wrap_angles

_ANGLE_SET = frozenset(ANGLES)
_ANGLES = list(ANGLES)


def _circular_mean(angles: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """Weighted mean of angle columns, through their unit vectors."""
    return np.arctan2(weights @ np.sin(angles), weights @ np.cos(angles))


def _sqrt_psd(m: np.ndarray) -> np.ndarray:
    """A lower-triangular L with L·Lᵀ = m; for a matrix rounding made slightly indefinite, the square root of
    its positive part instead."""
    try:
        return np.linalg.cholesky(m)
    except np.linalg.LinAlgError:
        vals, vecs = np.linalg.eigh((m + m.T) / 2)
        return vecs * np.sqrt(np.clip(vals, 0.0, None))


class Ukf(FilterBase):
    def __init__(self, alpha: float = 0.001, kappa: float = 0.0, beta: float = 2.0) -> None:
        super().__init__()
        self.set_constants(alpha, kappa, beta)
        self.sigma_points = np.zeros((2 * STATE_SIZE + 1, STATE_SIZE))
        self.uncorrected = True

    def set_constants(self, alpha: float, kappa: float, beta: float) -> None:
        n = STATE_SIZE
        self.lam = alpha * alpha * (n + kappa) - n
        count = 2 * n + 1
        self.state_weights = np.full(count, 1.0 / (2.0 * (n + self.lam)))
        self.state_weights[0] = self.lam / (n + self.lam)
        self.covariance_weights = self.state_weights.copy()
        self.covariance_weights[0] += 1.0 - alpha * alpha + beta

    def generate_sigma_points(self) -> None:
        root = _sqrt_psd((STATE_SIZE + self.lam) * self.covariance)
        x = self.state
        self.sigma_points = np.vstack((x, x + root.T, x - root.T))

    def predict(self, reference_ns: int, dt_s: float) -> None:
        self.prepare_control(reference_ns)
        self.generate_sigma_points()
        points = self.sigma_points
        if self.control is not None:
            points[:, VROLL:VROLL + 3] += self.control_acceleration[3:6] * dt_s
            for i in range(3):
                if self.control.update[i]:
                    points[:, AX + i] = self.control_acceleration[i]
        points = motion_model.project(points, dt_s)
        self.sigma_points = points
        w = self.state_weights
        x = w @ points
        x[_ANGLES] = _circular_mean(points[:, _ANGLES], w)
        self.state = x
        diff = points - x
        diff[:, _ANGLES] = wrap_angles(diff[:, _ANGLES])
        self.covariance = (diff.T * self.covariance_weights) @ diff + dt_s * self.process_noise_for(x)
        self.wrap_state_angles()
        self.uncorrected = True

    def correct(self, m: Measurement) -> None:
        # Several corrections may follow one prediction: later ones need sigma points of the corrected state.
        if not self.uncorrected:
            self.generate_sigma_points()
        idx = self.measured_indices(m)
        if not idx:
            return
        z = m.values[idx]
        r = self.measurement_covariance(m, idx)
        points = self.sigma_points
        w, wc = self.state_weights, self.covariance_weights
        predicted = points[:, idx]  # the measurement function picks the measured variables
        z_hat = w @ predicted
        angles = [k for k, i in enumerate(idx) if i in _ANGLE_SET]
        if angles:
            z_hat[angles] = _circular_mean(predicted[:, angles], w)
        dz = predicted - z_hat
        dx = points - self.state
        if angles:
            dz[:, angles] = wrap_angles(dz[:, angles])
        dx[:, _ANGLES] = wrap_angles(dx[:, _ANGLES])
        p_zz = (dz.T * wc) @ dz
        p_xz = (dx.T * wc) @ dz
        s_inv = np.linalg.inv(p_zz + r)
        gain = p_xz @ s_inv
        innovation = z - z_hat
        if angles:
            innovation[angles] = wrap_angles(innovation[angles])
        if not passes_mahalanobis(innovation, s_inv, m.mahalanobis_threshold):
            return
        self.state = self.state + gain @ innovation
        self.covariance = self.covariance - gain @ p_zz @ gain.T
        self.wrap_state_angles()
        self.uncorrected = False
