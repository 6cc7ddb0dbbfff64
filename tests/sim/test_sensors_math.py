"""Camera math without rendering: camera_info against PyBullet's own projection, depth → points against the
pinhole model that camera_info describes, the packed point layout byte by byte, Gazebo's topic names, and
the render-rate decision."""

from __future__ import annotations

import math
import struct

import numpy as np
import pybullet as pb
import pytest

from diffctl.description.model import CameraSpec, Sensor
from diffctl.description.pose import Pose
from diffctl.sim.flat_planes import camera_rays
from diffctl.sim.sensors import depth
from diffctl.sim.sensors.camera_info import (
    Intrinsics,
    camera_info_msg,
    camera_k,
    camera_p,
    gl_projection,
    intrinsics_from_fov,
    pixel_rays,
    render_intrinsics,
)
from diffctl.sim.sensors.rate import RenderRate
from diffctl.sim.sensors.topics import base_topic, outputs, sibling_camera_info


@pytest.mark.parametrize(("w", "h", "hfov"), [(800, 600, 1.047), (320, 240, 1.3962634), (640, 360, 2.0)])
def test_intrinsics_are_what_the_render_projection_implies(w: int, h: int, hfov: float) -> None:
    # The renderer's projection (PyBullet's, an independent OpenGL frustum), read back with gz-rendering's
    # projectionToCameraIntrinsic: fx = P00 W/2, fy = P11 H/2, cx = W (1 - P02)/2, cy = H/2 (1 + P12).
    spec = CameraSpec(width_px=w, height_px=h, horizontal_fov_rad=hfov)
    p = np.array(pb.computeProjectionMatrixFOV(math.degrees(spec.vertical_fov_rad), w / h, 0.1, 100)).reshape(4, 4).T
    intr = intrinsics_from_fov(w, h, hfov)
    assert intr.fx_px == pytest.approx(p[0, 0] * w / 2, rel=1e-6)
    assert intr.fy_px == pytest.approx(p[1, 1] * h / 2, rel=1e-6)
    assert intr.cx_px == pytest.approx(-w * (p[0, 2] - 1) / 2)
    assert intr.cy_px == pytest.approx(h + h * (p[1, 2] - 1) / 2)
    msg = camera_info_msg(5, "cam", w, h, intr)
    k, pp = msg["intrinsics"]["k"], msg["projection"]["p"]
    assert (k[0], k[2], k[4], k[5], k[8]) == (intr.fx_px, intr.cx_px, intr.fy_px, intr.cy_px, 1.0)
    assert (pp[0], pp[2], pp[3], pp[5], pp[6], pp[10]) == (intr.fx_px, intr.cx_px, 0.0, intr.fy_px, intr.cy_px, 1.0)
    assert msg["rectification_matrix"] == [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    assert msg["distortion"] == {"model": "PLUMB_BOB", "k": [0.0] * 5}


@pytest.mark.parametrize(("w", "h", "hfov"), [(800, 600, 1.047), (320, 240, 1.3962634), (64, 48, 2.0)])
def test_the_render_frustum_of_a_fov_is_pybullets_own(w: int, h: int, hfov: float) -> None:
    spec = CameraSpec(width_px=w, height_px=h, horizontal_fov_rad=hfov, clip_near_m=0.05, clip_far_m=30.0)
    ours = gl_projection(intrinsics_from_fov(w, h, hfov), w, h, 0.05, 30.0)
    theirs = pb.computeProjectionMatrixFOV(math.degrees(spec.vertical_fov_rad), w / h, 0.05, 30.0)
    assert np.allclose(ours, theirs, rtol=1e-6, atol=1e-9)
    assert np.allclose(pixel_rays(intrinsics_from_fov(w, h, hfov), w, h), camera_rays(w, h, spec.vertical_fov_rad))


def test_an_off_centre_skewed_lens_maps_each_ray_back_onto_its_pixel() -> None:
    """Through the GL frustum of K (what TinyRenderer draws with) every pixel's ray lands on that pixel."""
    w, h = 40, 30
    k = Intrinsics(fx_px=35.0, fy_px=33.0, cx_px=17.0, cy_px=18.5, skew_px=2.0)
    rays = pixel_rays(k, w, h)
    proj = np.array(gl_projection(k, w, h, 0.1, 10.0)).reshape(4, 4).T  # back to rows
    # sensor (x fwd, y left, z up) → GL eye (x right, y up, -z forward), 2 m along each ray
    eye = np.stack([-rays[1], rays[2], -rays[0], np.ones(w * h) / 2.0]) * 2.0
    clip = proj @ eye
    ndc = clip[:3] / clip[3]
    u, v = (ndc[0] + 1) * w / 2, (1 - ndc[1]) * h / 2
    cols, rows = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)
    assert np.allclose(u, cols.ravel()) and np.allclose(v, rows.ravel())
    assert np.all(np.abs(ndc[2]) < 1)  # inside the depth range


def test_lens_blocks_choose_k_p_and_the_render_pinhole() -> None:
    plain = CameraSpec(width_px=320, height_px=240, horizontal_fov_rad=1.047)
    assert camera_p(plain).p[:3] == [camera_k(plain).fx_px, 0.0, 160.0] and render_intrinsics(plain) == camera_k(plain)
    lens = CameraSpec(lens_intrinsics_px=(300.0, 310.0, 150.0, 110.0, 0.5))
    assert camera_k(lens).k == [300.0, 0.5, 150.0, 0.0, 310.0, 110.0, 0.0, 0.0, 1.0]
    assert camera_p(lens).p == [300.0, 0.0, 150.0, 0.0, 0.0, 310.0, 110.0, 0.0, 0.0, 0.0, 1.0, 0.0]
    stereo = CameraSpec(lens_projection_px=(280.0, 281.0, 161.0, 121.0, -14.0, 0.0))
    assert camera_p(stereo).p[3] == -14.0 and render_intrinsics(stereo).fx_px == 280.0
    assert camera_k(stereo) == intrinsics_from_fov(320, 240, 1.047)  # K from the fov, as Gazebo leaves it


def test_points_of_a_wall_project_back_onto_their_pixels_through_camera_info() -> None:
    """A wall 3 m ahead fills the view: every point has x = 3 and lies on the ray camera_info gives its pixel
    (ROS's optical frame: u right = -y, v down = -z), the way depth_image_proc would reconstruct it."""
    w, h, hfov, wall_m = 64, 48, 1.2, 3.0
    spec = CameraSpec(width_px=w, height_px=h, horizontal_fov_rad=hfov)
    rays = camera_rays(w, h, spec.vertical_fov_rad)
    pts = depth.sensor_points(np.full(w * h, wall_m), rays, 0.1, 100.0)
    intr = intrinsics_from_fov(w, h, hfov)
    u, v = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)  # pixel centres, row-major
    assert np.allclose(pts[:, 0], wall_m)
    assert np.allclose(-pts[:, 1], wall_m * (u.ravel() - intr.cx_px) / intr.fx_px, atol=1e-5)
    assert np.allclose(-pts[:, 2], wall_m * (v.ravel() - intr.cy_px) / intr.fy_px, atol=1e-5)
    img = depth.depth_image(pts, w, h)
    assert img.shape == (h, w) and img.dtype == np.float32 and np.all(img == np.float32(wall_m))


def test_clipping_as_gazebos_depth_shader() -> None:
    rays = np.array([[1.0, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 0.0]])
    # on axis: 5 m fine, 10 m (the far clip) and beyond → +inf, under near → -inf; off axis at 45° the
    # Euclidean length 9.9·√2 passes the far clip although x = 9.9 does not.
    pts = depth.sensor_points(np.array([5.0, 10.0, 0.05, 9.9]), rays, 0.1, 10.0)
    assert pts[0].tolist() == [5.0, 0.0, 0.0]
    assert np.all(pts[1] == np.inf) and np.all(pts[2] == -np.inf) and np.all(pts[3] == np.inf)


def test_packed_layout_byte_by_byte() -> None:
    pts = np.array([[1.5, -2.0, 0.25], [np.inf, np.inf, np.inf]], dtype=np.float32)
    rgb = np.array([[10, 20, 30], [200, 100, 0]], dtype=np.uint8)
    data = depth.pack_points(pts, rgb)
    assert len(data) == 2 * depth.POINT_STEP == 48
    x, y, z = struct.unpack_from("<fff", data, 0)
    assert (x, y, z) == (1.5, -2.0, 0.25)
    assert data[16:20] == bytes([30, 20, 10, 0])  # B, G, R, then the unwritten byte
    assert struct.unpack_from("<f", data, 24)[0] == math.inf and data[40:43] == bytes([0, 100, 200])
    back_pts, back_rgb = depth.unpack_points(data)
    assert np.array_equal(back_pts, pts) and np.array_equal(back_rgb, rgb)
    msg = depth.point_cloud_msg(7, "f", 2, 1, data)
    assert [(f["name"], f["offset"], f["datatype"], f["count"]) for f in msg["field"]] == [
        ("x", 0, "FLOAT32", 1),
        ("y", 4, "FLOAT32", 1),
        ("z", 8, "FLOAT32", 1),
        ("rgb", 16, "FLOAT32", 1),
    ]
    assert (msg["point_step"], msg["row_step"], msg["is_bigendian"]) == (24, 48, False)


def test_depth_grey_is_gazebos_depth_camera_colouring() -> None:
    g = depth.depth_grey(np.array([0.0, 2.0, 4.0, np.inf, -np.inf]))
    assert g[:, 0].tolist() == [255, 127, 0, 0, 0] and np.all(g[:, 0] == g[:, 2])


def _sensor(kind: str, topic: str = "", link: str = "cam_link", info_topic: str = "") -> Sensor:
    cam = CameraSpec(camera_info_topic=info_topic) if kind.endswith("camera") else None
    return Sensor("eye", kind, kind, link, topic, 10.0, True, False, Pose(), Pose(), camera=cam)


def test_topics_as_gazebo_names_them() -> None:
    default = "/world/w/model/m/link/cam_link/sensor/eye"

    def topics(s: Sensor) -> dict[str, str]:
        return {o.name: o.topic for o in outputs(s, base_topic(s, "w", "m"))}

    assert topics(_sensor("rgbd_camera")) == {
        "image": default + "/image",
        "depth_image": default + "/depth_image",
        "points": default + "/points",
        "camera_info": default + "/camera_info",
    }
    assert topics(_sensor("rgbd_camera", "/rgbd")) == {
        "image": "/rgbd/image",
        "depth_image": "/rgbd/depth_image",
        "points": "/rgbd/points",
        "camera_info": "/rgbd/camera_info",
    }
    assert topics(_sensor("camera")) == {"image": default + "/image", "camera_info": default + "/camera_info"}
    assert topics(_sensor("camera", "/camera")) == {"image": "/camera", "camera_info": "/camera_info"}
    assert topics(_sensor("camera", "/front/image_raw", info_topic="/front/info"))["camera_info"] == "/front/info"
    assert topics(_sensor("depth_camera", "/depth")) == {
        "depth_image": "/depth",
        "points": "/depth/points",
        "camera_info": "/camera_info",
    }
    assert topics(_sensor("depth_camera"))["depth_image"] == default + "/depth_image"
    assert topics(_sensor("lidar")) == {"scan": default + "/scan", "points": default + "/scan/points"}
    assert topics(_sensor("lidar", "/lidar")) == {"scan": "/lidar", "points": "/lidar/points"}
    nested = "/world/w/model/m/model/inner/link/body/sensor/eye/imu"
    assert topics(_sensor("imu", link="inner::body")) == {"imu": nested}
    assert sibling_camera_info("/a/b/c") == "/a/b/camera_info"


def test_render_rate_lowers_once_to_what_fits_and_never_at_full_speed() -> None:
    step = 1_000_000
    rate = RenderRate(requested_period_ns=10 * step, step_ns=step)  # 100 Hz asked
    assert rate.observe(0.5, 1.0) is None  # the first frame is not counted
    assert rate.observe(0.04, 1.0) is None  # warming up
    # 40 ms a frame at real time may use half of the wall clock: one frame every 80 ms of sim time.
    assert rate.observe(0.04, 1.0) == 80 * step and rate.lowered
    assert rate.observe(0.04, 1.0) is None  # it holds
    fast = RenderRate(requested_period_ns=10 * step, step_ns=step)
    assert [fast.observe(0.04, 0.0) for _ in range(5)] == [None] * 5  # rtf 0: no wall-clock target
    cheap = RenderRate(requested_period_ns=100 * step, step_ns=step)
    assert [cheap.observe(0.01, 1.0) for _ in range(5)] == [None] * 5 and not cheap.lowered
