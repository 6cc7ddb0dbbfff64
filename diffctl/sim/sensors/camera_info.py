"""A camera's pinhole model as gz-sensors sets it up: K, P, the render projection, per-pixel rays, and the
gz.msgs.CameraInfo built from them (pure math, no rendering).

K is `<lens><intrinsics>` when given, else what gz-rendering's `projectionToCameraIntrinsic` reads back from
the symmetric frustum of `<horizontal_fov>` and the image's aspect ratio: fx = fy = W / (2 tan(hfov / 2)),
cx = W / 2, cy = H / 2. P is `<lens><projection>` when given, else K with Tx = Ty = 0. The image is rendered
through P's frustum when given, else K's (CameraSensor::UpdateLensIntrinsicsAndProjection). Distortion is
PLUMB_BOB with k = [k1, k2, p1, p2, k3]; R is the identity. Pixel (i, j) has its centre at (i + 0.5, j + 0.5).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from diffctl.bus import gz
from diffctl.description.model import CameraSpec


@dataclass(frozen=True)
class Intrinsics:
    fx_px: float
    fy_px: float
    cx_px: float
    cy_px: float
    skew_px: float = 0.0

    @property
    def k(self) -> list[float]:
        return [self.fx_px, self.skew_px, self.cx_px, 0.0, self.fy_px, self.cy_px, 0.0, 0.0, 1.0]


@dataclass(frozen=True)
class Projection:
    fx_px: float
    fy_px: float
    cx_px: float
    cy_px: float
    tx_px: float = 0.0
    ty_px: float = 0.0

    @property
    def p(self) -> list[float]:
        return [
            *(self.fx_px, 0.0, self.cx_px, self.tx_px),
            *(0.0, self.fy_px, self.cy_px, self.ty_px),
            *(0.0, 0.0, 1.0, 0.0),
        ]


def focal_length_px(width_px: int, horizontal_fov_rad: float) -> float:
    return width_px / (2.0 * math.tan(horizontal_fov_rad / 2.0))


def intrinsics_from_fov(width_px: int, height_px: int, horizontal_fov_rad: float) -> Intrinsics:
    f = focal_length_px(width_px, horizontal_fov_rad)
    return Intrinsics(f, f, width_px / 2.0, height_px / 2.0)


def camera_k(spec: CameraSpec) -> Intrinsics:
    if spec.lens_intrinsics_px is not None:
        return Intrinsics(*spec.lens_intrinsics_px)
    return intrinsics_from_fov(spec.width_px, spec.height_px, spec.horizontal_fov_rad)


def camera_p(spec: CameraSpec) -> Projection:
    if spec.lens_projection_px is not None:
        return Projection(*spec.lens_projection_px)
    k = camera_k(spec)
    return Projection(k.fx_px, k.fy_px, k.cx_px, k.cy_px)


def render_intrinsics(spec: CameraSpec) -> Intrinsics:
    """The pinhole the image is drawn with (the projection's when given; it has no skew)."""
    if spec.lens_projection_px is not None:
        p = camera_p(spec)
        return Intrinsics(p.fx_px, p.fy_px, p.cx_px, p.cy_px)
    return camera_k(spec)


def gl_projection(k: Intrinsics, width_px: int, height_px: int, near_m: float, far_m: float) -> list[float]:
    """The OpenGL projection matrix (column-major, as PyBullet takes it) whose image is `k`'s: eye x right,
    y up, looking down -z; pixel v grows downwards."""
    w, h = width_px, height_px
    rows = [
        [2 * k.fx_px / w, -2 * k.skew_px / w, 1 - 2 * k.cx_px / w, 0.0],
        [0.0, 2 * k.fy_px / h, 2 * k.cy_px / h - 1, 0.0],
        [0.0, 0.0, (far_m + near_m) / (near_m - far_m), 2 * far_m * near_m / (near_m - far_m)],
        [0.0, 0.0, -1.0, 0.0],
    ]
    return [rows[r][c] for c in range(4) for r in range(4)]


def pixel_rays(k: Intrinsics, width_px: int, height_px: int) -> np.ndarray:
    """Per-pixel ray directions in the sensor frame (+x forward, +y left, +z up), forward component 1,
    row-major from the top-left pixel, one contiguous row per axis: shape (3, h * w)."""
    v, u = np.meshgrid(np.arange(height_px) + 0.5, np.arange(width_px) + 0.5, indexing="ij")
    down = (v - k.cy_px) / k.fy_px
    right = (u - k.cx_px - k.skew_px * down) / k.fx_px
    return np.ascontiguousarray(np.stack([np.ones(u.size), -right.ravel(), -down.ravel()]))


IDENTITY_3X3 = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]


def camera_info_msg(
    sim_time_ns: int,
    frame: str,
    width_px: int,
    height_px: int,
    k: Intrinsics,
    p: Projection | None = None,
    distortion: tuple[float, ...] = (0.0, 0.0, 0.0, 0.0, 0.0),
) -> dict:
    p = p or Projection(k.fx_px, k.fy_px, k.cx_px, k.cy_px)
    return {
        "header": gz.header(sim_time_ns, frame),
        "width": width_px,
        "height": height_px,
        "distortion": {"model": "PLUMB_BOB", "k": list(distortion)},
        "intrinsics": {"k": k.k},
        "projection": {"p": p.p},
        "rectification_matrix": list(IDENTITY_3X3),
    }
