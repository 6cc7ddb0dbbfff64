"""Depth images and packed point clouds from one rendered frame, as Gazebo Harmonic's depth shader makes them
(pure numpy, no rendering).

gz-rendering's ogre2 depth camera reconstructs each pixel's point in the sensor frame (+x forward, +y left,
+z up, the frame the SDF pose gives: not an optical frame). The depth image holds x, the distance along the
view axis, in metres (R_FLOAT32). A point farther than the far clip (Euclidean length) becomes +inf on all
three axes, one nearer than the near clip along x becomes -inf (`depth_camera_fs.glsl`). Point clouds are
gz.msgs.PointCloudPacked laid out by `InitPointCloudPacked(.., aligned=true, {xyz, rgb})`: x@0, y@4, z@8,
rgb@16, all FLOAT32, 24 bytes a point, row-major from the top-left pixel; the colour's bytes are B, G, R in
little-endian order (PointCloudUtil::FillMsg).
"""

from __future__ import annotations

import numpy as np

from diffctl.bus import gz

# The shader's tolerance at the clip planes.
CLIP_TOLERANCE_M = 1e-6
POINT_STEP = 24
POINT_FIELDS = (("x", 0), ("y", 4), ("z", 8), ("rgb", 16))
_POINT_DTYPE = np.dtype(
    {
        "names": ["x", "y", "z", "b", "g", "r"],
        "formats": ["<f4", "<f4", "<f4", "u1", "u1", "u1"],
        "offsets": [0, 4, 8, 16, 17, 18],
        "itemsize": POINT_STEP,
    }
)


def sensor_points(depth_fwd_m: np.ndarray, rays: np.ndarray, near_m: float, far_m: float) -> np.ndarray:
    """Per-pixel points in the sensor frame, shape (n, 3) float32, from the forward distance of each pixel
    (n,) and its ray (3, n) with forward component 1 (`flat_planes.camera_rays`); clipped as Gazebo clips."""
    d = np.asarray(depth_fwd_m, dtype=np.float32)
    pts = np.empty((d.size, 3), dtype=np.float32)
    pts[:, 0] = d
    np.multiply(d, rays[1], out=pts[:, 1], casting="unsafe")
    np.multiply(d, rays[2], out=pts[:, 2], casting="unsafe")
    # Squared lengths against the squared far clip: no square root over the whole frame.
    far = np.einsum("ij,ij->i", pts, pts) > (far_m - CLIP_TOLERANCE_M) ** 2
    near = ~far & (d < near_m + CLIP_TOLERANCE_M)
    pts[far] = np.inf
    pts[near] = -np.inf
    return pts


def clip_depth(points: np.ndarray, near_m: float | None, far_m: float | None) -> None:
    """An rgbd camera's `<depth_camera><clip>`, in place: depth beyond `far_m` becomes +inf, nearer than
    `near_m` -inf, on all three axes (RgbdCameraSensor applies it to the depth buffer, then the points)."""
    x = points[:, 0]
    if far_m is not None:
        points[x > far_m] = np.inf
    if near_m is not None:
        points[x < near_m] = -np.inf


def depth_image(points: np.ndarray, width_px: int, height_px: int) -> np.ndarray:
    """The depth image (height, width) float32 metres: each point's x (±inf where clipped)."""
    return np.ascontiguousarray(points[:, 0]).reshape(height_px, width_px)


def pack_points(points: np.ndarray, rgb: np.ndarray) -> bytes:
    """PointCloudPacked data of `points` (n, 3) float32 and their colours (n, 3) uint8 R, G, B."""
    # Six 4-byte words a point: x, y, z, padding, colour, padding.
    out = np.zeros((len(points), POINT_STEP // 4), dtype="<f4")
    out[:, :3] = points
    colour = rgb.astype("<u4")
    # Little-endian R << 16 | G << 8 | B puts the bytes B, G, R, 0 in memory.
    out.view("<u4")[:, 4] = (colour[:, 0] << 16) | (colour[:, 1] << 8) | colour[:, 2]
    return out.tobytes()


def unpack_points(data: bytes) -> tuple[np.ndarray, np.ndarray]:
    """Inverse of `pack_points`: (points (n, 3) float32, rgb (n, 3) uint8)."""
    arr = np.frombuffer(data, dtype=_POINT_DTYPE)
    return (
        np.stack([arr["x"], arr["y"], arr["z"]], axis=1),
        np.stack([arr["r"], arr["g"], arr["b"]], axis=1),
    )


def depth_grey(depth_m: np.ndarray) -> np.ndarray:
    """depth_camera's point colours: grey 255 - 255 d / (largest finite d), black where d is not finite
    (DepthCameraSensor ConvertDepthToImage). Shape (n, 3) uint8."""
    d = np.asarray(depth_m, dtype=np.float64).reshape(-1)
    finite = np.isfinite(d)
    top = float(d[finite].max()) if finite.any() else 0.0
    grey = np.zeros(d.size, dtype=np.uint8)
    if top > 0:
        grey[finite] = np.clip(255.0 - d[finite] * (255.0 / top), 0, 255).astype(np.uint8)
    return np.repeat(grey[:, None], 3, axis=1)


def point_cloud_msg(sim_time_ns: int, frame: str, width_px: int, height_px: int, data: bytes) -> dict:
    return {
        "header": gz.header(sim_time_ns, frame),
        "field": [{"name": n, "offset": off, "datatype": "FLOAT32", "count": 1} for n, off in POINT_FIELDS],
        "height": height_px,
        "width": width_px,
        "is_bigendian": False,
        "point_step": POINT_STEP,
        "row_step": POINT_STEP * width_px,
        "data": data,
        # Gazebo's rgbd and depth cameras set is_dense true whatever the clipping wrote (RgbdCameraSensor.cc).
        "is_dense": True,
    }
