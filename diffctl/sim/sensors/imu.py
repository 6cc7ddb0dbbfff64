"""IMU sensors: orientation, angular velocity and linear acceleration of the sensor frame, with SDF noise.

Gazebo's IMU noise: per axis a constant bias drawn once per run from N(bias_mean, bias_stddev) with a random
sign, plus white Gaussian noise; all from the sensor's own seeded numpy Generator.
"""

from __future__ import annotations

import numpy as np
import pybullet as pb

from diffctl.bus import gz
from diffctl.description.model import Noise, Sensor
from diffctl.description.pose import Quat, Vec3, quat_multiply, quat_normalize, quat_rotate
from diffctl.sim.entity import Entity
from diffctl.sim.sensors.common import frame_id


class NormalStream:
    """Standard normal draws from a numpy Generator, taken in blocks: the same values in the same order as one
    `standard_normal(3)` per axis triple, without numpy's per-call cost at every IMU sample."""

    BLOCK = 768

    def __init__(self, rng: np.random.Generator) -> None:
        self.rng = rng
        self._buf: list[float] = []
        self._i = 0

    def take3(self) -> tuple[float, float, float]:
        i = self._i
        if i + 3 > len(self._buf):
            self._buf = self.rng.standard_normal(self.BLOCK).tolist()
            i = 0
        self._i = i + 3
        b = self._buf
        return b[i], b[i + 1], b[i + 2]


class ImuNoise:
    """Gazebo's IMU noise on three axes: a constant bias per axis (drawn once, random sign) plus white noise."""

    def __init__(
        self, noises: tuple[Noise, Noise, Noise], rng: np.random.Generator, normals: NormalStream | None = None
    ) -> None:
        self.active = any(n.active for n in noises)
        mean = [n.mean if n.active else 0.0 for n in noises]
        self.stddev = tuple(n.stddev if n.active else 0.0 for n in noises)
        bias = []
        for n in noises:
            b = rng.normal(n.bias_mean, n.bias_stddev) if n.bias_stddev > 0 else n.bias_mean
            bias.append((b if rng.random() < 0.5 else -b) if n.active else 0.0)
        self.bias = tuple(float(b) for b in bias)
        # bias + mean, added to every sample
        self._offset = tuple(b + m for b, m in zip(self.bias, mean, strict=True))
        self.normals = normals or NormalStream(rng)

    def apply(self, v: Vec3) -> Vec3:
        if not self.active:
            return v
        z0, z1, z2 = self.normals.take3()
        o, sd = self._offset, self.stddev
        return (v[0] + o[0] + sd[0] * z0, v[1] + o[1] + sd[1] * z1, v[2] + o[2] + sd[2] * z2)


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
        # One stream for both, drawn in the order samples use it (acceleration, then angular velocity).
        normals = NormalStream(rng)
        self.gyro_noise = ImuNoise(spec.angular_velocity_noise, rng, normals)
        self.accel_noise = ImuNoise(spec.linear_acceleration_noise, rng, normals)
        self.body, self.link, offset = entity.link_frame(sensor.link)
        # The sensor frame in the centre-of-mass frame PyBullet reports, composed once.
        self._in_com = entity.inertial_frame(self.body, self.link).inverse().compose(offset).compose(sensor.pose_link)
        self._prev: tuple[int, Vec3] | None = None

    def reset(self) -> None:
        self._prev = None

    def _com(self) -> tuple[Quat, Vec3, Vec3]:
        """(orientation of the centre-of-mass frame, velocity of the sensor point, angular velocity), in world
        axes: PyBullet's numbers with no Pose built per call."""
        cid, body, link = self.entity.client, self.body, self.link
        if link < 0:
            _, orn = pb.getBasePositionAndOrientation(body, physicsClientId=cid)
            lin, ang = pb.getBaseVelocity(body, physicsClientId=cid)
        else:
            st = pb.getLinkState(body, link, computeLinkVelocity=1, computeForwardKinematics=1, physicsClientId=cid)
            orn, lin, ang = st[1], st[6], st[7]
        r = quat_rotate(orn, self._in_com.xyz)  # the sensor point from the centre of mass
        return orn, point_velocity(lin, ang, r), ang

    def remember(self, sim_time_ns: int) -> None:
        """Record the sensor point's velocity now, for the acceleration of the next sample (one step later)."""
        self._prev = (sim_time_ns, self._com()[1])

    def sample(self, sim_time_ns: int) -> dict:
        orn, v, w = self._com()
        accel: Vec3 = (0.0, 0.0, 0.0)
        if self._prev is not None and sim_time_ns > self._prev[0]:
            dt = (sim_time_ns - self._prev[0]) * 1e-9
            pv = self._prev[1]
            accel = ((v[0] - pv[0]) / dt, (v[1] - pv[1]) / dt, (v[2] - pv[2]) / dt)
        self._prev = (sim_time_ns, v)
        q = quat_normalize(quat_multiply(orn, self._in_com.quat))
        to_sensor = (-q[0], -q[1], -q[2], q[3])
        f = self.accel_noise.apply(quat_rotate(to_sensor, specific_force(accel, self.gravity)))
        g = self.gyro_noise.apply(quat_rotate(to_sensor, w))
        return {
            "header": gz.header(sim_time_ns, self.frame_id),
            "entity_name": self.frame_id,
            "orientation": {"x": q[0], "y": q[1], "z": q[2], "w": q[3]},
            "angular_velocity": {"x": g[0], "y": g[1], "z": g[2]},
            "linear_acceleration": {"x": f[0], "y": f[1], "z": f[2]},
        }
