"""What every simulated sensor shares: its header frame id, its pose in gz.msgs form, scalar noise."""

from __future__ import annotations

import numpy as np

from diffctl.description.model import Noise, Sensor
from diffctl.description.pose import Pose


def frame_id(model_name: str, sensor: Sensor) -> str:
    """Gazebo's header frame id: `<gz_frame_id>` (or the older `<frame_id>`), else the scoped sensor name
    without the world, `model::link::sensor` (gz-sensors Sensor.cc)."""
    return sensor.frame_id or f"{model_name}::{sensor.link}::{sensor.name}"


def pose_msg(p: Pose) -> dict:
    return {
        "position": {"x": p.xyz[0], "y": p.xyz[1], "z": p.xyz[2]},
        "orientation": {"x": p.quat[0], "y": p.quat[1], "z": p.quat[2], "w": p.quat[3]},
    }


def rotation(p: Pose) -> list[list[float]]:
    """The 3x3 rotation of `p`."""
    return [row[:3] for row in p.to_matrix()[:3]]


class ScalarNoise:
    """gz-sensors' Gaussian noise on one value: a bias drawn once (from N(bias_mean, bias_stddev), with a
    random sign) plus white noise N(mean, stddev) per sample; inactive noise returns the value as it is."""

    def __init__(self, noise: Noise, rng: np.random.Generator) -> None:
        self.noise, self.rng = noise, rng
        self.bias = 0.0
        if noise.active:
            b = rng.normal(noise.bias_mean, noise.bias_stddev) if noise.bias_stddev > 0 else noise.bias_mean
            self.bias = b if rng.random() < 0.5 else -b

    def apply(self, value: float) -> float:
        n = self.noise
        if not n.active:
            return value
        return value + self.bias + (float(self.rng.normal(n.mean, n.stddev)) if n.stddev > 0 else n.mean)
