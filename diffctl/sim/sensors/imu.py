"""IMU sensors: orientation, angular velocity and linear acceleration of the sensor frame, with SDF noise.

Gazebo's IMU noise: per axis a constant bias drawn once per run from N(bias_mean, bias_stddev) with a random
sign, plus white Gaussian noise; all from the sensor's own seeded numpy Generator.
"""

from __future__ import annotations

import numpy as np

from diffctl.bus import gz
from diffctl.description.model import Noise, Sensor
from diffctl.description.pose import Pose, Vec3
from diffctl.sim.entity import Entity
from diffctl.sim.sensors.common import frame_id


class ImuNoise:
    """Gazebo's IMU noise on three axes: a constant bias per axis (drawn once, random sign) plus white noise."""

    def __init__(self, noises: tuple[Noise, Noise, Noise], rng: np.random.Generator) -> None:
        self.active = any(n.active for n in noises)
        self.mean = np.array([n.mean if n.active else 0.0 for n in noises])
        self.stddev = np.array([n.stddev if n.active else 0.0 for n in noises])
        bias = []
        for n in noises:
            b = rng.normal(n.bias_mean, n.bias_stddev) if n.bias_stddev > 0 else n.bias_mean
            bias.append((b if rng.random() < 0.5 else -b) if n.active else 0.0)
        self.bias = np.array(bias)
        self.rng = rng

    def apply(self, v: Vec3) -> Vec3:
        if not self.active:
            return v
        out = np.array(v) + self.bias + self.mean + self.stddev * self.rng.standard_normal(3)
        return (float(out[0]), float(out[1]), float(out[2]))


def specific_force(accel_world: Vec3, gravity: Vec3) -> Vec3:
    """What an accelerometer measures (in world axes): acceleration minus gravity; +g upward at rest."""
    return (accel_world[0] - gravity[0], accel_world[1] - gravity[1], accel_world[2] - gravity[2])


def point_velocity(lin: Vec3, ang: Vec3, r: Vec3) -> Vec3:
    """Velocity of a point at `r` from the centre of mass of a body moving with (lin, ang)."""
    return (
        lin[0] + ang[1] * r[2] - ang[2] * r[1],
        lin[1] + ang[2] * r[0] - ang[0] * r[2],
        lin[2] + ang[0] * r[1] - ang[1] * r[0],
    )


class Imu:
    """Orientation, angular velocity and linear acceleration of the sensor frame, with SDF noise.

    Acceleration is the finite difference of the sensor point's velocity since `remember` (called one physics
    step before each sample) or the previous sample; the first sample of a run reads gravity alone."""

    def __init__(self, entity: Entity, sensor: Sensor, gravity: Vec3, rng: np.random.Generator) -> None:
        spec = sensor.imu
        assert spec is not None
        self.entity, self.sensor, self.gravity = entity, sensor, gravity
        self.frame_id = frame_id(entity.name, sensor)
        self.gyro_noise = ImuNoise(spec.angular_velocity_noise, rng)
        self.accel_noise = ImuNoise(spec.linear_acceleration_noise, rng)
        self.body, self.link, offset = entity.link_frame(sensor.link)
        # The sensor frame in the centre-of-mass frame PyBullet reports, composed once.
        self._in_com = entity.inertial_frame(self.body, self.link).inverse().compose(offset).compose(sensor.pose_link)
        self._prev: tuple[int, Vec3] | None = None

    def reset(self) -> None:
        self._prev = None

    def _state(self) -> tuple[Pose, Vec3, Vec3]:
        com, lin, ang = self.entity.com_state(self.body, self.link)
        pose = com.compose(self._in_com)
        r = (pose.xyz[0] - com.xyz[0], pose.xyz[1] - com.xyz[1], pose.xyz[2] - com.xyz[2])
        return pose, point_velocity(lin, ang, r), ang

    def remember(self, sim_time_ns: int) -> None:
        """Record the sensor point's velocity now, for the acceleration of the next sample (one step later)."""
        self._prev = (sim_time_ns, self._state()[1])

    def sample(self, sim_time_ns: int) -> dict:
        pose, v, w = self._state()
        accel: Vec3 = (0.0, 0.0, 0.0)
        if self._prev is not None and sim_time_ns > self._prev[0]:
            dt = (sim_time_ns - self._prev[0]) * 1e-9
            pv = self._prev[1]
            accel = ((v[0] - pv[0]) / dt, (v[1] - pv[1]) / dt, (v[2] - pv[2]) / dt)
        self._prev = (sim_time_ns, v)
        inv = pose.inverse()
        f = self.accel_noise.apply(inv.rotate(specific_force(accel, self.gravity)))
        g = self.gyro_noise.apply(inv.rotate(w))
        q = pose.quat
        return {
            "header": gz.header(sim_time_ns, self.frame_id),
            "entity_name": self.frame_id,
            "orientation": {"x": q[0], "y": q[1], "z": q[2], "w": q[3]},
            "angular_velocity": {"x": g[0], "y": g[1], "z": g[2]},
            "linear_acceleration": {"x": f[0], "y": f[1], "z": f[2]},
        }
