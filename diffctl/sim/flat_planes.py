"""Ground planes drawn into camera images by ray casting, not by TinyRenderer (pure numpy).

TinyRenderer scans the screen bounding box of every triangle, and a ground plane seen from a car's camera
spans the whole screen from under the lens: it costs most of a frame (8 of 10 ms at 320x240, measured).
A flat, uniformly coloured plane is cheaper to draw directly: intersect each pixel's ray with it, keep the
nearer of it and what TinyRenderer drew (linearised depth buffer), paint it in the colour TinyRenderer
would shade it with (sampled once). Headless worlds therefore give plane visuals to this module instead of
to PyBullet.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from diffctl.description.pose import Pose, Vec3


@dataclass(frozen=True)
class FlatPlane:
    """A rectangle of a visual plane, in world coordinates."""

    origin: Vec3
    normal: Vec3  # unit
    u: Vec3  # unit in-plane axes
    v: Vec3
    half_u_m: float
    half_v_m: float
    rgba: tuple[float, float, float, float]

    @staticmethod
    def from_pose(pose: Pose, size_m: tuple[float, float], rgba: tuple[float, float, float, float]) -> FlatPlane:
        """A plane whose frame is `pose` (its normal along the frame's +z), `size_m` along x and y."""
        return FlatPlane(
            pose.xyz,
            pose.rotate((0, 0, 1)),
            pose.rotate((1, 0, 0)),
            pose.rotate((0, 1, 0)),
            size_m[0] / 2,
            size_m[1] / 2,
            rgba,
        )


def camera_rays(width_px: int, height_px: int, vertical_fov_rad: float) -> np.ndarray:
    """Per-pixel ray directions in the camera frame (+x forward, +y left, +z up), forward component 1,
    row-major from the top-left pixel, one contiguous row per axis: shape (3, h * w)."""
    tan_v = math.tan(vertical_fov_rad / 2)
    tan_h = tan_v * width_px / height_px
    xs = (2 * (np.arange(width_px) + 0.5) / width_px - 1) * tan_h  # to the right
    ys = (1 - 2 * (np.arange(height_px) + 0.5) / height_px) * tan_v  # up
    yy, xx = np.meshgrid(ys, xs, indexing="ij")
    return np.ascontiguousarray(np.stack([np.ones_like(xx).ravel(), -xx.ravel(), yy.ravel()]))


def linear_depth_m(depth_buffer: np.ndarray, near_m: float, far_m: float) -> np.ndarray:
    """Distance along the view axis from an OpenGL-style [0, 1] depth buffer."""
    return far_m * near_m / (far_m - (far_m - near_m) * depth_buffer)


def _dot(rows: np.ndarray | tuple, v: np.ndarray) -> np.ndarray:
    # Element-wise on per-axis rows: BLAS matmul on (N, 3) shapes is slow, and slower still when its
    # threads fight other processes for two cores (24 ms instead of 0.4, measured).
    return rows[0] * v[0] + rows[1] * v[1] + rows[2] * v[2]


def composite(
    rgb: np.ndarray,
    depth_m: np.ndarray,
    rays_cam: np.ndarray,
    camera_pose: Pose,
    planes: list[tuple[FlatPlane, np.ndarray]],
    near_m: float,
    far_m: float,
) -> None:
    """Paint `planes` (each with its shaded RGB colour) into `rgb` (h, w, 3) where they are nearer than
    `depth_m` (h, w); both are updated in place. `rays_cam` comes from `camera_rays`."""
    if not planes:
        return
    flat_rgb = rgb.reshape(-1, 3)
    flat_depth = depth_m.reshape(-1)
    m = np.array(camera_pose.to_matrix())
    dirs = (_dot(rays_cam, m[0, :3]), _dot(rays_cam, m[1, :3]), _dot(rays_cam, m[2, :3]))
    eye = np.array(camera_pose.xyz)
    for plane, colour in planes:
        n = np.array(plane.normal)
        denom = _dot(dirs, n)
        with np.errstate(divide="ignore", invalid="ignore"):
            t = float((np.array(plane.origin) - eye) @ n) / denom
        hit = (t > near_m) & (t < far_m) & (t < flat_depth)
        if not hit.any():
            continue
        idx = np.nonzero(hit)[0]
        th = t[idx]
        rel = eye - np.array(plane.origin)
        points = (rel[0] + dirs[0][idx] * th, rel[1] + dirs[1][idx] * th, rel[2] + dirs[2][idx] * th)
        inside = (np.abs(_dot(points, np.array(plane.u))) <= plane.half_u_m) & (
            np.abs(_dot(points, np.array(plane.v))) <= plane.half_v_m
        )
        idx = idx[inside]
        flat_rgb[idx] = colour
        flat_depth[idx] = th[inside]
