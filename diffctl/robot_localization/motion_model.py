"""The constant-acceleration 3D motion model of robot_localization's filters and its Jacobian.

Position moves by the body velocity and acceleration rotated into the world (Rz·Ry·Rx of the orientation),
orientation by the body rates through the Euler-rate matrix, velocity by the acceleration. Everything else
is held. `transfer` is the linear map x' = F·x for the current orientation; `jacobian` adds the partial
derivatives of the rotated terms with respect to roll, pitch and yaw.
"""

from __future__ import annotations

import math

import numpy as np

from diffctl.robot_localization.rotations import rot_x, rot_y, rot_z
from diffctl.robot_localization.state import AX, PITCH, ROLL, STATE_SIZE, VROLL, VX, X

_I3 = np.eye(3)


def euler_rates(roll: float, pitch: float) -> np.ndarray:
    """Body angular velocity → (roll, pitch, yaw) rates."""
    sr, cr = math.sin(roll), math.cos(roll)
    sec = 1.0 / math.cos(pitch)
    tp = math.sin(pitch) * sec
    return np.array(((1.0, sr * tp, cr * tp), (0.0, cr, -sr), (0.0, sr * sec, cr * sec)))


def transfer(state: np.ndarray, dt: float) -> np.ndarray:
    """F for one prediction of `dt` seconds from `state` (15×15)."""
    roll, pitch, yaw = state[ROLL], state[ROLL + 1], state[ROLL + 2]
    rot = rot_z(yaw) @ rot_y(pitch) @ rot_x(roll)
    f = np.eye(STATE_SIZE)
    f[X:X + 3, VX:VX + 3] = rot * dt
    f[X:X + 3, AX:AX + 3] = rot * (0.5 * dt * dt)
    f[ROLL:ROLL + 3, VROLL:VROLL + 3] = euler_rates(roll, pitch) * dt
    f[VX:VX + 3, AX:AX + 3] = _I3 * dt
    return f


def _d_rot_x(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array(((0.0, 0.0, 0.0), (0.0, -s, -c), (0.0, c, -s)))


def _d_rot_y(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array(((-s, 0.0, c), (0.0, 0.0, 0.0), (-c, 0.0, -s)))


def _d_rot_z(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array(((-s, -c, 0.0), (c, -s, 0.0), (0.0, 0.0, 0.0)))


def jacobian(state: np.ndarray, dt: float, f: np.ndarray) -> np.ndarray:
    """∂f(x)/∂x at `state`, given F = transfer(state, dt)."""
    roll, pitch, yaw = state[ROLL], state[PITCH], state[PITCH + 1]
    rx, ry, rz = rot_x(roll), rot_y(pitch), rot_z(yaw)
    travel = state[VX:VX + 3] * dt + state[AX:AX + 3] * (0.5 * dt * dt)  # body-frame displacement
    j = f.copy()
    j[X:X + 3, ROLL] = rz @ ry @ _d_rot_x(roll) @ travel
    j[X:X + 3, PITCH] = rz @ _d_rot_y(pitch) @ rx @ travel
    j[X:X + 3, PITCH + 1] = _d_rot_z(yaw) @ ry @ rx @ travel
    wy, wz = state[VROLL + 1], state[VROLL + 2]  # the roll rate enters the roll row linearly only
    sr, cr = math.sin(roll), math.cos(roll)
    sec = 1.0 / math.cos(pitch)
    tp = math.sin(pitch) * sec
    # Derivatives of the Euler-rate rows (roll, pitch, yaw rates) by roll and by pitch.
    j[ROLL, ROLL] += (cr * tp * wy - sr * tp * wz) * dt
    j[ROLL, PITCH] += (sec * sec * (sr * wy + cr * wz)) * dt
    j[PITCH, ROLL] += (-sr * wy - cr * wz) * dt
    j[PITCH + 1, ROLL] += (cr * sec * wy - sr * sec * wz) * dt
    j[PITCH + 1, PITCH] += (tp * sec * (sr * wy + cr * wz)) * dt
    return j


def project(states: np.ndarray, dt: float) -> np.ndarray:
    """f(x) for many states at once (rows), each through its own transfer: the UKF's sigma points."""
    r, p, y = states[:, ROLL], states[:, PITCH], states[:, PITCH + 1]
    sr, cr, sp, cp, sy, cy = np.sin(r), np.cos(r), np.sin(p), np.cos(p), np.sin(y), np.cos(y)
    rot = np.stack((
        np.stack((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr), axis=-1),
        np.stack((sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr), axis=-1),
        np.stack((-sp, cp * sr, cp * cr), axis=-1),
    ), axis=1)
    sec = 1.0 / cp
    tp = sp * sec
    zero, one = np.zeros_like(r), np.ones_like(r)
    rates = np.stack((
        np.stack((one, sr * tp, cr * tp), axis=-1),
        np.stack((zero, cr, -sr), axis=-1),
        np.stack((zero, sr * sec, cr * sec), axis=-1),
    ), axis=1)
    v, w, a = states[:, VX:VX + 3], states[:, VROLL:VROLL + 3], states[:, AX:AX + 3]
    out = states.copy()
    out[:, X:X + 3] += np.einsum("nij,nj->ni", rot, v * dt + a * (0.5 * dt * dt))
    out[:, ROLL:ROLL + 3] += np.einsum("nij,nj->ni", rates, w * dt)
    out[:, VX:VX + 3] += a * dt
    return out
