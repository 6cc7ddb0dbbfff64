"""CPU sensors: lidar by one `rayTestBatch` per scan, IMU from link velocities, camera by TinyRenderer.

Each sensor reads the physics world when asked (`sample(sim_time_ns)`) and returns its gz.msgs message as a
dict; publishing and scheduling belong to the runner. Noise follows SDF/Gazebo: Gaussian with `mean` and
`stddev`, plus for the IMU a bias drawn once per run from N(bias_mean, bias_stddev) with a random sign. All
randomness comes from one seeded numpy Generator, so a seed reproduces every sample.
"""

from __future__ import annotations

import base64
import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pybullet as pb

from diffctl.bus import gz
from diffctl.description.model import Noise, Sensor
from diffctl.description.pose import Pose, Vec3, quat_from_matrix
from diffctl.errors import DescriptionError
from diffctl.sim.entity import Entity
from diffctl.sim.flat_planes import FlatPlane, camera_rays, composite, linear_depth_m

RANGE_DECIMALS = 4
# PyBullet caps one rayTestBatch at this many rays (SharedMemoryPublic.h).
MAX_RAYS = 16384
# Camera noise is drawn from a pre-computed table (a fresh normal() per 230k pixels costs more than the render).
NOISE_TABLE_SIZE = 1 << 20
# Shaded colours of flat planes, by (rgba, normal, light): the same for every camera of the process.
_PLANE_RGB: dict[tuple, np.ndarray] = {}


def _frame_id(entity: Entity, s: Sensor) -> str:
    # Gazebo's default frame is the scoped sensor name; <gz_frame_id> overrides it.
    return s.frame_id or f"{entity.name}::{s.link}::{s.name}"


def _pose_msg(p: Pose) -> dict:
    return {
        "position": {"x": p.xyz[0], "y": p.xyz[1], "z": p.xyz[2]},
        "orientation": {"x": p.quat[0], "y": p.quat[1], "z": p.quat[2], "w": p.quat[3]},
    }


def lidar_directions(
    h_samples: int, h_min: float, h_max: float, v_samples: int, v_min: float, v_max: float
) -> np.ndarray:
    """Unit ray directions in the sensor frame, horizontal index fastest (Gazebo's range order), shape (n, 3)."""
    h = np.linspace(h_min, h_max, h_samples) if h_samples > 1 else np.array([h_min])
    v = np.linspace(v_min, v_max, v_samples) if v_samples > 1 else np.array([v_min])
    vv, hh = np.meshgrid(v, h, indexing="ij")
    return np.stack([np.cos(vv) * np.cos(hh), np.cos(vv) * np.sin(hh), np.sin(vv)], axis=-1).reshape(-1, 3)


def ranges_from_hits(fractions: np.ndarray, hit: np.ndarray, range_min_m: float, range_max_m: float) -> np.ndarray:
    """Ranges of rays cast from range_min to range_max: +inf where nothing was hit (as Gazebo reports)."""
    r = range_min_m + fractions * (range_max_m - range_min_m)
    return np.where(hit, r, np.inf)


class Lidar:
    """gpu_lidar / lidar / ray sensors. Rays start at range_min so the sensor never sees its own housing."""

    def __init__(self, entity: Entity, sensor: Sensor, rng: np.random.Generator) -> None:
        spec = sensor.lidar
        assert spec is not None
        self.entity, self.sensor, self.spec, self.rng = entity, sensor, spec, rng
        self.frame_id = _frame_id(entity, sensor)
        self.count = spec.horizontal_samples * spec.vertical_samples
        if self.count > MAX_RAYS:
            raise DescriptionError(
                f"lidar {sensor.name!r} casts {self.count} rays per scan; PyBullet allows at most {MAX_RAYS}",
                field=f"sensor {sensor.name}",
                hint="lower <horizontal><samples> or <vertical><samples>",
            )
        self.body, self.link, offset = entity.link_frame(sensor.link)
        # rayTestBatch takes rays relative to a link in that link's centre-of-mass frame.
        inertial = entity.inertial_frame(self.body, self.link)
        in_com = inertial.inverse().compose(offset).compose(sensor.pose_link)
        d = lidar_directions(
            spec.horizontal_samples,
            spec.horizontal_min_angle_rad,
            spec.horizontal_max_angle_rad,
            spec.vertical_samples,
            spec.vertical_min_angle_rad,
            spec.vertical_max_angle_rad,
        )
        rot = np.array(_matrix(in_com))
        origin = np.array(in_com.xyz)
        world_dirs = d @ rot.T
        self._from = (origin + world_dirs * spec.range_min_m).tolist()
        self._to = (origin + world_dirs * spec.range_max_m).tolist()
        self._noise = spec.noise if spec.noise.active else None
        self._step = spec.angle_increment_rad
        v_n = spec.vertical_samples
        self._v_step = (spec.vertical_max_angle_rad - spec.vertical_min_angle_rad) / (v_n - 1) if v_n > 1 else 0.0

    def scan(self) -> np.ndarray:
        """Ranges in metres (with noise when the SDF asks for it), +inf where nothing is within range."""
        res = pb.rayTestBatch(
            self._from,
            self._to,
            parentObjectUniqueId=self.body,
            parentLinkIndex=self.link,
            physicsClientId=self.entity.client,
        )
        # One pass over the result tuples: a miss has fraction 1 and object -1; mark it with fraction 2.
        frac = np.fromiter((r[2] if r[0] >= 0 else 2.0 for r in res), dtype=np.float64, count=self.count)
        ranges = ranges_from_hits(frac, frac < 1.5, self.spec.range_min_m, self.spec.range_max_m)
        if self._noise is not None:
            n = self._noise
            ranges = ranges + self.rng.normal(n.mean, n.stddev, self.count) if n.stddev > 0 else ranges + n.mean
            ranges = np.clip(ranges, self.spec.range_min_m, None)
        return ranges

    def sample(self, sim_time_ns: int) -> dict:
        s = self.spec
        ranges = self.scan()
        pose = self.entity.link_pose(self.sensor.link).compose(self.sensor.pose_link)
        return {
            "header": gz.header(sim_time_ns, self.frame_id),
            "frame": self.frame_id,
            "world_pose": _pose_msg(pose),
            "angle_min": s.horizontal_min_angle_rad,
            "angle_max": s.horizontal_max_angle_rad,
            "angle_step": self._step,
            "range_min": s.range_min_m,
            "range_max": s.range_max_m,
            "count": s.horizontal_samples,
            "vertical_angle_min": s.vertical_min_angle_rad,
            "vertical_angle_max": s.vertical_max_angle_rad,
            "vertical_angle_step": self._v_step,
            "vertical_count": s.vertical_samples,
            # 0.1 mm is below any lidar's resolution, and short numbers halve the encoding time.
            "ranges": np.round(ranges, RANGE_DECIMALS).tolist(),
            "intensities": [],
        }


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
        self.frame_id = _frame_id(entity, sensor)
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


class Camera:
    """An RGB camera looking along the sensor's +x with +z up (Gazebo's convention), rendered on the CPU.

    `planes()` lists the flat planes PyBullet was not given (headless worlds): they are ray cast into each
    frame (flat_planes.py), in the colour TinyRenderer gives them, sampled once per colour and normal.
    """

    def __init__(
        self,
        entity: Entity,
        sensor: Sensor,
        rng: np.random.Generator,
        light_direction: Vec3,
        planes: Callable[[], list[FlatPlane]] | None = None,
    ) -> None:
        spec = sensor.camera
        assert spec is not None
        self.entity, self.sensor, self.spec = entity, sensor, spec
        self.planes = planes or (lambda: [])
        self.frames = 0
        self._rays = camera_rays(spec.width_px, spec.height_px, spec.vertical_fov_rad)
        self.frame_id = _frame_id(entity, sensor)
        self.width, self.height = spec.width_px, spec.height_px
        self._proj = pb.computeProjectionMatrixFOV(
            fov=math.degrees(spec.vertical_fov_rad),
            aspect=self.width / self.height,
            nearVal=spec.clip_near_m,
            farVal=spec.clip_far_m,
        )
        # PyBullet wants the position the light comes from; SDF gives the direction the light travels.
        self._light = [-light_direction[0] * 10, -light_direction[1] * 10, -light_direction[2] * 10]
        self._noise: np.ndarray | None = None
        if spec.noise.active:
            table = rng.normal(spec.noise.mean * 255.0, spec.noise.stddev * 255.0, NOISE_TABLE_SIZE)
            self._noise = np.round(table).astype(np.int16)
        self.rng = rng

    def _tiny(self, eye: Vec3, fwd: Vec3, up: Vec3, width: int, height: int, proj: Any) -> tuple[Any, Any]:
        view = pb.computeViewMatrix(eye, (eye[0] + fwd[0], eye[1] + fwd[1], eye[2] + fwd[2]), up)
        _, _, rgba, depth, _ = pb.getCameraImage(
            width,
            height,
            view,
            proj,
            lightDirection=self._light,
            shadow=0,
            renderer=pb.ER_TINY_RENDERER,
            flags=pb.ER_NO_SEGMENTATION_MASK,
            physicsClientId=self.entity.client,
        )
        return rgba, depth

    def plane_colour(self, plane: FlatPlane) -> np.ndarray:
        """The RGB TinyRenderer shades `plane` with, rendered once on a sample quad in a scratch client (so the
        world's bodies, and so its collision-pair order, never depend on whether a camera was watched)."""
        key = (plane.rgba, plane.normal, tuple(self._light))
        if key not in _PLANE_RGB:
            cid = pb.connect(pb.DIRECT)
            try:
                n, u = plane.normal, plane.u
                quad = pb.createVisualShape(
                    pb.GEOM_MESH,
                    vertices=[[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]],
                    indices=[0, 1, 2, 0, 2, 3],
                    normals=[[0, 0, 1]] * 4,
                    rgbaColor=plane.rgba,
                    physicsClientId=cid,
                )
                frame = Pose((0.0, 0.0, 0.0), quat_from_matrix(np.array([u, np.cross(n, u), n]).T.tolist()))
                pb.createMultiBody(0, -1, quad, basePosition=frame.xyz, baseOrientation=frame.quat, physicsClientId=cid)
                # Seen at 45°, as a ground is from a car: TinyRenderer's specular term is small there.
                d = (np.array(n) + np.array(u)) / math.sqrt(2)
                up = (np.array(n) - np.array(u)) / math.sqrt(2)
                view = pb.computeViewMatrix(tuple(d), (0.0, 0.0, 0.0), tuple(up))
                proj = pb.computeProjectionMatrixFOV(fov=10, aspect=1, nearVal=0.1, farVal=10)
                _, _, rgba, _, _ = pb.getCameraImage(
                    5,
                    5,
                    view,
                    proj,
                    lightDirection=self._light,
                    shadow=0,
                    renderer=pb.ER_TINY_RENDERER,
                    flags=pb.ER_NO_SEGMENTATION_MASK,
                    physicsClientId=cid,
                )
                _PLANE_RGB[key] = np.asarray(rgba, dtype=np.uint8).reshape(5, 5, 4)[2, 2, :3].copy()
            finally:
                pb.disconnect(cid)
        return _PLANE_RGB[key]

    def render(self) -> np.ndarray:
        """The current image, (height, width, 3) uint8."""
        pose = self.entity.link_pose(self.sensor.link).compose(self.sensor.pose_link)
        fwd = pose.rotate((1.0, 0.0, 0.0))
        up = pose.rotate((0.0, 0.0, 1.0))
        rgba, depth = self._tiny(pose.xyz, fwd, up, self.width, self.height, self._proj)
        self.frames += 1
        rgb = np.array(rgba, dtype=np.uint8).reshape(self.height, self.width, 4)[:, :, :3].copy()
        planes = self.planes()
        if planes:
            near, far = self.spec.clip_near_m, self.spec.clip_far_m
            depth_m = linear_depth_m(np.asarray(depth, dtype=np.float64).reshape(self.height, self.width), near, far)
            composite(rgb, depth_m, self._rays, pose, [(p, self.plane_colour(p)) for p in planes], near, far)
        if self._noise is None:
            return rgb
        n = rgb.size
        start = int(self.rng.integers(0, NOISE_TABLE_SIZE - n)) if n < NOISE_TABLE_SIZE else 0
        noise = np.resize(self._noise[start : start + n], n).reshape(rgb.shape)
        return np.clip(rgb.astype(np.int16) + noise, 0, 255).astype(np.uint8)

    def sample(self, sim_time_ns: int) -> dict:
        img = self.render()
        return {
            "header": gz.header(sim_time_ns, self.frame_id),
            "width": self.width,
            "height": self.height,
            "step": self.width * 3,
            "pixel_format_type": "RGB_INT8",
            "data": base64.b64encode(img.tobytes()).decode("ascii"),
        }


def _matrix(p: Pose) -> list[list[float]]:
    return [row[:3] for row in p.to_matrix()[:3]]
