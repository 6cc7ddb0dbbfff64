"""The EKF and UKF cores against robot_localization's own filter tests (test_ekf.cpp, test_ukf.cpp,
test_filter_base.cpp): the first measurement initializes the state and covariance exactly; a second one,
twice the first with variance 1e-9, is tracked within 1e-3 one nanosecond later."""

from __future__ import annotations

import math

import numpy as np
import pytest

from diffctl.robot_localization import motion_model
from diffctl.robot_localization.ekf import Ekf
from diffctl.robot_localization.estimator import Estimator
from diffctl.robot_localization.filter_base import Measurement, control_acceleration
from diffctl.robot_localization.state import STATE_SIZE
from diffctl.robot_localization.ukf import Ukf


@pytest.mark.parametrize("make", [Ekf, Ukf], ids=["ekf", "ukf"])
def test_measurements_as_upstream_filter_tests(make) -> None:
    filt = make()
    est = Estimator(filt)
    filt.covariance = np.eye(STATE_SIZE) * 0.5
    z = np.array([i * 0.01 * STATE_SIZE for i in range(STATE_SIZE)])
    r = np.eye(STATE_SIZE) * 1e-9
    est.enqueue(Measurement("odom0", 1000, z, r, [True] * STATE_SIZE, sys_max()))
    est.integrate(1001)
    assert np.array_equal(filt.state, z)
    assert np.array_equal(filt.covariance, r)
    filt.covariance = np.eye(STATE_SIZE) * 0.5
    est.enqueue(Measurement("odom0", 1002, 2 * z, r, [True] * STATE_SIZE, sys_max()))
    est.integrate(1003)
    assert np.all(np.abs(2 * z - filt.state) < 0.001), 2 * z - filt.state


def sys_max() -> float:
    import sys

    return sys.float_info.max


def test_jacobian_is_the_derivative_of_the_motion_model() -> None:
    # The analytic Jacobian against central differences of x' = F(x)·x.
    rng = np.random.default_rng(7)
    x = rng.normal(size=STATE_SIZE) * 0.7
    dt = 0.05
    j = motion_model.jacobian(x, dt, motion_model.transfer(x, dt))
    numeric = np.zeros((STATE_SIZE, STATE_SIZE))
    for i in range(STATE_SIZE):
        h = np.zeros(STATE_SIZE)
        h[i] = 1e-6
        numeric[:, i] = (motion_model.transfer(x + h, dt) @ (x + h) - motion_model.transfer(x - h, dt) @ (x - h)) / 2e-6
    assert np.allclose(j, numeric, atol=1e-6)
    # and the UKF's batch projection is the same model
    assert np.allclose(motion_model.project(x[None, :], dt)[0], motion_model.transfer(x, dt) @ x)


def test_control_acceleration_follows_limits_and_gains() -> None:
    # accelerating toward the command: the gain times the error, capped by the acceleration limit
    assert control_acceleration(0.0, 1.0, 1.3, 0.8, 2.0, 1.5) == pytest.approx(0.8)
    assert control_acceleration(0.0, 10.0, 1.3, 0.8, 2.0, 1.5) == pytest.approx(1.3)
    # slowing down uses the deceleration pair; a command of the other sign brakes toward zero first
    assert control_acceleration(1.0, 0.5, 1.3, 0.8, 2.0, 1.5) == pytest.approx(-0.75)
    assert control_acceleration(1.0, -1.0, 1.3, 0.8, 2.0, 1.5) == pytest.approx(-2.0)


def test_a_rejection_threshold_keeps_outliers_out() -> None:
    filt = Ekf()
    est = Estimator(filt)
    r = np.eye(STATE_SIZE) * 0.01
    update = [True] + [False] * (STATE_SIZE - 1)
    est.enqueue(Measurement("pose0", 1_000_000, np.zeros(STATE_SIZE), r, update, 2.0))
    est.integrate(1_000_000)
    far = np.zeros(STATE_SIZE)
    far[0] = 5.0  # 5 m against a 0.1 m standard deviation: far beyond 2 sigma
    est.enqueue(Measurement("pose0", 2_000_000, far, r, update, 2.0))
    est.integrate(2_000_000)
    assert abs(filt.state[0]) < 1e-6
    near = np.zeros(STATE_SIZE)
    near[0] = 0.05
    est.enqueue(Measurement("pose0", 3_000_000, near, r, update, 2.0))
    est.integrate(3_000_000)
    assert 0.0 < filt.state[0] <= 0.05 + 1e-9
    assert math.isfinite(filt.covariance[0, 0])
