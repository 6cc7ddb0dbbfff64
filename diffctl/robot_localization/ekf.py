"""The extended Kalman filter of ekf_node: the motion model linearized at the state, a linear measurement of
the measured variables, the covariance updated in Joseph form."""

from __future__ import annotations

import numpy as np

from diffctl.robot_localization import motion_model
from diffctl.robot_localization.filter_base import FilterBase, Measurement, passes_mahalanobis
from diffctl.robot_localization.state import ANGLES, AX, VROLL, wrap_angles

_ANGLE_SET = frozenset(ANGLES)


class Ekf(FilterBase):
    def predict(self, reference_ns: int, dt_s: float) -> None:
        x = self.state
        f = motion_model.transfer(x, dt_s)
        j = motion_model.jacobian(x, dt_s, f)
        q = self.process_noise_for(x)
        self.prepare_control(reference_ns)
        if self.control is not None:
            x[VROLL:VROLL + 3] += self.control_acceleration[3:6] * dt_s
            for i in range(3):
                if self.control.update[i]:
                    x[AX + i] = self.control_acceleration[i]
        self.state = f @ x
        self.wrap_state_angles()
        self.covariance = j @ self.covariance @ j.T + dt_s * q

    def correct(self, m: Measurement) -> None:
        idx = self.measured_indices(m)
        if not idx:
            return
        z = m.values[idx]
        r = self.measurement_covariance(m, idx)
        p = self.covariance
        pht = p[:, idx]  # P·Hᵀ: H picks the measured variables
        s_inv = np.linalg.inv(pht[idx, :] + r)
        gain = pht @ s_inv
        innovation = z - self.state[idx]
        angles = [k for k, i in enumerate(idx) if i in _ANGLE_SET]
        if angles:
            innovation[angles] = wrap_angles(innovation[angles])
        if not passes_mahalanobis(innovation, s_inv, m.mahalanobis_threshold):
            return
        self.state = self.state + gain @ innovation
        # Joseph form (I-KH)·P·(I-KH)ᵀ + K·R·Kᵀ, with H picking columns: (I-KH)·P = P - K·P[idx], then
        # ·(I-KH)ᵀ = A - A[:, idx]·Kᵀ — two thin products instead of two full 15×15 ones.
        a = p - gain @ p[idx, :]
        self.covariance = a - a[:, idx] @ gain.T + gain @ r @ gain.T
        self.wrap_state_angles()
