"""camera, depth_camera and rgbd_camera sensors: every output of one sensor from one render per due tick.

Follows gz-sensors' Update(): camera_info is published to whoever listens without rendering; nothing is
rendered when no image, depth image or point cloud has a subscriber; one render feeds all of them, and only
the outputs someone subscribes to are encoded. Headers carry `<optical_frame_id>` when given, else the
sensor's frame id (a relabelling only: points stay in the x-forward sensor frame, as in Gazebo).
"""

from __future__ import annotations

import numpy as np

from diffctl.bus import gz
from diffctl.sim.sensors import depth as depth_math
from diffctl.sim.sensors.camera import Camera
from diffctl.sim.sensors.camera_info import camera_info_msg, camera_k, camera_p
from diffctl.sim.sensors.topics import DEPTH, IMAGE, INFO, POINTS

RENDERED = frozenset({IMAGE, DEPTH, POINTS})
# SDF <image><format> of a plain camera → gz.msgs.PixelFormatType and channels.
IMAGE_FORMATS = {
    "R8G8B8": ("RGB_INT8", 3),
    "RGB_INT8": ("RGB_INT8", 3),
    "B8G8R8": ("BGR_INT8", 3),
    "BGR_INT8": ("BGR_INT8", 3),
    "L8": ("L_INT8", 1),
    "L_INT8": ("L_INT8", 1),
}


def grey(rgb: np.ndarray) -> np.ndarray:
    """ITU-R BT.601 luma of an (h, w, 3) uint8 image, (h, w) uint8."""
    y = rgb[..., 0] * 0.299 + rgb[..., 1] * 0.587 + rgb[..., 2] * 0.114
    return np.clip(np.round(y), 0, 255).astype(np.uint8)


_CONVERT = {"L_INT8": grey, "BGR_INT8": lambda rgb: rgb[..., ::-1]}


def image_msg(sim_time_ns: int, frame: str, pixels: np.ndarray, pixel_format: str, bytes_per_px: int) -> dict:
    h, w = pixels.shape[:2]
    return {
        "header": gz.header(sim_time_ns, frame),
        "width": w,
        "height": h,
        "step": w * bytes_per_px,
        "pixel_format_type": pixel_format,
        "data": np.ascontiguousarray(pixels).tobytes(),
    }


class CameraSensor:
    """The outputs of one camera-type sensor (`kind` is camera, depth_camera or rgbd_camera)."""

    def __init__(self, camera: Camera) -> None:
        self.camera = camera
        spec = camera.spec
        self.kind = camera.sensor.type
        self.name = f"{camera.entity.name}::{camera.sensor.link}::{camera.sensor.name}"
        self.frame = camera.frame_id
        self.width, self.height = spec.width_px, spec.height_px
        self.k, self.p = camera_k(spec), camera_p(spec)
        self.notes: list[str] = []  # what of the SDF is not simulated, one line each
        self.distortion = spec.distortion
        if self.kind == "camera" and any(spec.distortion):
            # Gazebo distorts a plain camera's image; we render an ideal pinhole, and say so in camera_info
            # too, so that rectifying the image leaves it as it is. (Depth and rgbd cameras are not
            # distorted in Gazebo either, and report the SDF's coefficients as it does.)
            self.notes.append("<distortion> is not simulated: the image is an ideal pinhole, camera_info says so")
            self.distortion = (0.0, 0.0, 0.0, 0.0, 0.0)
        fmt = spec.format.upper()
        # rgbd_camera images are always RGB (RgbdCameraSensor); a format we cannot produce falls back to RGB.
        if self.kind == "camera" and fmt not in IMAGE_FORMATS:
            self.notes.append(
                f"image format {spec.format!r} is not simulated, publishing RGB_INT8 (simulated: R8G8B8, B8G8R8, L8)"
            )
        self.pixel_format, self.bytes_per_px = IMAGE_FORMATS.get(fmt, IMAGE_FORMATS["R8G8B8"])
        if self.kind == "rgbd_camera":
            self.pixel_format, self.bytes_per_px = IMAGE_FORMATS["R8G8B8"]
        # <depth_camera><clip> narrows an rgbd camera's depth (RgbdCameraSensor); depth_camera ignores it.
        self.depth_clip_m = spec.depth_clip_m if self.kind == "rgbd_camera" else (None, None)

    @property
    def frames(self) -> int:
        return self.camera.frames

    def needs_render(self, wanted: set[str]) -> bool:
        return bool(wanted & RENDERED)

    def messages(self, sim_time_ns: int, wanted: set[str]) -> dict[str, dict]:
        """The messages of the `wanted` outputs now, rendering at most once."""
        out: dict[str, dict] = {}
        if INFO in wanted:
            out[INFO] = camera_info_msg(
                sim_time_ns, self.frame, self.width, self.height, self.k, self.p, self.distortion
            )
        if not self.needs_render(wanted):
            return out
        spatial = bool(wanted & {DEPTH, POINTS})
        frame = self.camera.render_frame(depth=spatial)
        if IMAGE in wanted:
            pixels = _CONVERT.get(self.pixel_format, np.asarray)(frame.rgb)
            out[IMAGE] = image_msg(sim_time_ns, self.frame, pixels, self.pixel_format, self.bytes_per_px)
        if not spatial:
            return out
        assert frame.depth_fwd_m is not None
        spec = self.camera.spec
        points = depth_math.sensor_points(frame.depth_fwd_m, self.camera.rays, spec.clip_near_m, spec.clip_far_m)
        depth_math.clip_depth(points, *self.depth_clip_m)
        if DEPTH in wanted:
            d = depth_math.depth_image(points, self.width, self.height)
            out[DEPTH] = image_msg(sim_time_ns, self.frame, d.astype("<f4"), "R_FLOAT32", 4)
        if POINTS in wanted:
            depth_only = self.kind == "depth_camera"
            colours = depth_math.depth_grey(points[:, 0]) if depth_only else frame.rgb.reshape(-1, 3)
            data = depth_math.pack_points(points, colours)
            out[POINTS] = depth_math.point_cloud_msg(sim_time_ns, self.frame, self.width, self.height, data)
        return out
