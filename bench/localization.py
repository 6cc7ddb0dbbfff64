"""robot_localization's filters, pure: the cost of one measurement cycle (predict to the measurement's time,
then correct), as ekf_node and ukf_node run it for each wheel-odometry or IMU message.

Keys, microseconds per measurement, best of 5: `ekf_update_us` (a body-velocity measurement: vx, vy, vyaw,
after a 20 ms prediction), `ekf_pose_update_us` (x, y, yaw), `ukf_update_us` (the vx, vy, vyaw one).
"""

from __future__ import annotations

import json
import timeit

import numpy as np

from diffctl.robot_localization.ekf import Ekf
from diffctl.robot_localization.filter_base import FilterBase, Measurement
from diffctl.robot_localization.state import STATE_SIZE, VX, VY, VYAW, YAW, X, Y
from diffctl.robot_localization.ukf import Ukf

STEP_NS = 20_000_000


def _cycle_us(make: type[FilterBase], measured: tuple[int, ...], n: int) -> float:
    filt = make()
    update = [i in measured for i in range(STATE_SIZE)]
    values = np.zeros(STATE_SIZE)
    values[VX], values[VYAW] = 0.4, 0.4
    cov = np.eye(STATE_SIZE) * 1e-3
    filt.process(Measurement("odom0", STEP_NS, values, cov, update))
    t = [STEP_NS]

    def one() -> None:
        t[0] += STEP_NS
        filt.process(Measurement("odom0", t[0], values, cov, update))

    return min(timeit.repeat(one, number=n, repeat=5)) / n * 1e6


def run() -> dict:
    return {
        "ekf_update_us": round(_cycle_us(Ekf, (VX, VY, VYAW), 2000), 1),
        "ekf_pose_update_us": round(_cycle_us(Ekf, (X, Y, YAW), 2000), 1),
        "ukf_update_us": round(_cycle_us(Ukf, (VX, VY, VYAW), 300), 1),
    }


if __name__ == "__main__":
    print(json.dumps(run(), indent=1))
