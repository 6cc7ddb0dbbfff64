"""The 15-element state robot_localization estimates: indices, names, angle wrapping, default process noise.

Order: x y z, roll pitch yaw (world frame), vx vy vz, vroll vpitch vyaw (body frame), ax ay az (body frame).
"""

from __future__ import annotations

import math

import numpy as np

STATE_SIZE = 15
X, Y, Z, ROLL, PITCH, YAW, VX, VY, VZ, VROLL, VPITCH, VYAW, AX, AY, AZ = range(STATE_SIZE)
POSE_SIZE = TWIST_SIZE = 6
NAMES = ("X", "Y", "Z", "ROLL", "PITCH", "YAW", "X_VELOCITY", "Y_VELOCITY", "Z_VELOCITY", "ROLL_VELOCITY",
         "PITCH_VELOCITY", "YAW_VELOCITY", "X_ACCELERATION", "Y_ACCELERATION", "Z_ACCELERATION")
ANGLES = (ROLL, PITCH, YAW)
# The filters' own process noise when the parameter is not given (per second of prediction).
DEFAULT_PROCESS_NOISE_DIAGONAL = (0.05, 0.05, 0.06, 0.03, 0.03, 0.06, 0.025, 0.025, 0.04, 0.01, 0.01, 0.02,
                                  0.01, 0.01, 0.015)


def wrap_angle(a: float) -> float:
    """`a` in [-π, π), as the angles package normalizes."""
    a = math.fmod(a + math.pi, math.tau)
    if a < 0.0:
        a += math.tau
    return a - math.pi


def wrap_angles(v: np.ndarray) -> np.ndarray:
    """Elementwise wrap_angle of an array (a new array)."""
    w = np.fmod(v + math.pi, math.tau)
    w = np.where(w < 0.0, w + math.tau, w)
    return w - math.pi


def default_process_noise() -> np.ndarray:
    return np.diag(DEFAULT_PROCESS_NOISE_DIAGONAL)
