"""The CPU renderer behind every camera-type sensor: PyBullet's TinyRenderer plus ray-cast ground planes.

A camera looks along its sensor frame's +x with +z up (Gazebo's convention). One `render_frame()` gives the
colour image and each pixel's distance along the view axis, from which the depth image and the point cloud
are derived (depth.py); `Camera.sample` is the plain RGB camera's gz.msgs.Image. Image noise follows
gz-sensors: Gaussian on colour for `camera` (mean and stddev in [0, 1] of full scale), on depth in metres for
`depth_camera` and `rgbd_camera`; drawn from a pre-computed table of the sensor's own seeded Generator.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pybullet as pb

from diffctl.bus import gz
from diffctl.description.model import Sensor
from diffctl.description.pose import Pose, Vec3, quat_from_matrix
from diffctl.sim.entity import Entity
from diffctl.sim.flat_planes import FlatPlane, composite, linear_depth_m
from diffctl.sim.sensors.camera_info import gl_projection, pixel_rays, render_intrinsics
from diffctl.sim.sensors.common import frame_id

# Noise is drawn from a pre-computed table (a fresh normal() per 230k pixels costs more than the render).
NOISE_TABLE_SIZE = 1 << 20
_DRAW_LATER = object()  # a noise table not drawn yet
# Shaded colours of flat planes, by (rgba, normal, light): the same for every camera of the process.
_PLANE_RGB: dict[tuple, np.ndarray] = {}


@dataclass(frozen=True)
class Frame:
    rgb: np.ndarray  # (height, width, 3) uint8
    depth_fwd_m: np.ndarray | None  # (height * width,) distance along the view axis; the far clip where empty


class Camera:
    """Renders what a camera-type sensor sees. `planes()` lists the flat planes PyBullet was not given
    (headless worlds): they are ray cast into each frame (flat_planes.py), in the colour TinyRenderer gives
    them, sampled once per colour and normal."""

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
        self.frame_id = spec.optical_frame_id or frame_id(entity.name, sensor)
        self.width, self.height = spec.width_px, spec.height_px
        # One pinhole for TinyRenderer's frustum, the ray-cast planes and the points derived from depth.
        k = render_intrinsics(spec)
        self.rays = pixel_rays(k, self.width, self.height)
        self._proj = gl_projection(k, self.width, self.height, spec.clip_near_m, spec.clip_far_m)
        # PyBullet wants the position the light comes from; SDF gives the direction the light travels.
        self._light = [-light_direction[0] * 10, -light_direction[1] * 10, -light_direction[2] * 10]
        self.rng = rng
        # The noise tables are drawn at the first frame (a million normals: ~15 ms of the robot's spawn, for a
        # camera nobody may watch); nothing draws from this sensor's generator before, so the frames are the same.
        self._noise: np.ndarray | object | None = None
        self._depth_noise: np.ndarray | object | None = None
        n = spec.noise
        if n.active and sensor.type == "camera":
            self._noise = _DRAW_LATER
        elif n.active:
            self._depth_noise = _DRAW_LATER

    def _draw_noise_tables(self) -> None:
        n = self.spec.noise
        if self._noise is _DRAW_LATER:
            self._noise = np.round(self.rng.normal(n.mean * 255.0, n.stddev * 255.0, NOISE_TABLE_SIZE)).astype(np.int16)
        if self._depth_noise is _DRAW_LATER:
            self._depth_noise = self.rng.normal(n.mean, n.stddev, NOISE_TABLE_SIZE)

    def _tiny(self, eye: Vec3, fwd: Vec3, up: Vec3) -> tuple[Any, Any]:
        view = pb.computeViewMatrix(eye, (eye[0] + fwd[0], eye[1] + fwd[1], eye[2] + fwd[2]), up)
        _, _, rgba, depth, _ = pb.getCameraImage(
            self.width,
            self.height,
            view,
            self._proj,
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

    def pose(self) -> Pose:
        return self.entity.link_pose(self.sensor.link).compose(self.sensor.pose_link)

    def render_frame(self, *, depth: bool) -> Frame:
        """One render of the current scene; with `depth`, also each pixel's distance along the view axis."""
        if self._noise is _DRAW_LATER or self._depth_noise is _DRAW_LATER:
            self._draw_noise_tables()
        pose = self.pose()
        rgba, buffer = self._tiny(pose.xyz, pose.rotate((1.0, 0.0, 0.0)), pose.rotate((0.0, 0.0, 1.0)))
        self.frames += 1
        rgb = np.array(rgba, dtype=np.uint8).reshape(self.height, self.width, 4)[:, :, :3].copy()
        planes = self.planes()
        depth_m = None
        if planes or depth:
            near, far = self.spec.clip_near_m, self.spec.clip_far_m
            depth_m = linear_depth_m(np.asarray(buffer, dtype=np.float64).reshape(self.height, self.width), near, far)
            composite(rgb, depth_m, self.rays, pose, [(p, self.plane_colour(p)) for p in planes], near, far)
            depth_m = depth_m.reshape(-1)
        if self._noise is not None:
            rgb = np.clip(rgb.astype(np.int16) + self._table_slice(self._noise, rgb.size).reshape(rgb.shape), 0, 255)
            rgb = rgb.astype(np.uint8)
        if depth and depth_m is not None and self._depth_noise is not None:
            depth_m = depth_m + self._table_slice(self._depth_noise, depth_m.size)
        return Frame(rgb, depth_m if depth else None)

    def _table_slice(self, table: np.ndarray, n: int) -> np.ndarray:
        start = int(self.rng.integers(0, NOISE_TABLE_SIZE - n)) if n < NOISE_TABLE_SIZE else 0
        return np.resize(table[start : start + n], n)

    def render(self) -> np.ndarray:
        """The current colour image, (height, width, 3) uint8."""
        return self.render_frame(depth=False).rgb

    def sample(self, sim_time_ns: int) -> dict:
        """The plain camera's gz.msgs.Image (RGB_INT8, raw bytes)."""
        img = self.render()
        return {
            "header": gz.header(sim_time_ns, self.frame_id),
            "width": self.width,
            "height": self.height,
            "step": self.width * 3,
            "pixel_format_type": "RGB_INT8",
            "data": img.tobytes(),
        }
