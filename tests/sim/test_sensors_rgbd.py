"""rgbd_camera and depth_camera in a real PyBullet world: a red wall in front of the camera is where its
depth, points and camera_info say, in the sensor frame, from one render; nothing renders without demand."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from sim_helpers import build, sdf_world

from diffctl.sim.sensors import Camera, CameraSensor, CameraTask, RenderRate
from diffctl.sim.sensors.depth import unpack_points
from diffctl.sim.stepper import Task

W, H, HFOV, NEAR, FAR = 160, 120, 1.047, 0.1, 10.0
CAM_Z = 0.5
WALL_DIST, WALL_THICK, WALL_HALF = 2.0, 0.2, 0.5  # wall centre distance, thickness; half width and height
FACE = WALL_DIST - WALL_THICK / 2


def rig(kind: str, yaw: float, extra: str = "", lens: str = "") -> str:
    return f"""<model name="rig"><static>true</static><pose>0 0 {CAM_Z} 0 0 {yaw}</pose><link name="l">
      <sensor name="eye" type="{kind}"><update_rate>10</update_rate>
        <camera><horizontal_fov>{HFOV}</horizontal_fov><image><width>{W}</width><height>{H}</height></image>
          <clip><near>{NEAR}</near><far>{FAR}</far></clip>{lens}</camera></sensor>{extra}
    </link></model>"""


def wall(yaw: float) -> str:
    x, y = WALL_DIST * math.cos(yaw), WALL_DIST * math.sin(yaw)
    return f"""<model name="wall"><static>true</static><pose>{x} {y} {WALL_HALF} 0 0 {yaw}</pose><link name="l">
      <visual name="v"><geometry><box><size>{WALL_THICK} {2 * WALL_HALF} {2 * WALL_HALF}</size></box></geometry>
        <material><diffuse>1 0 0 1</diffuse><ambient>1 0 0 1</ambient></material></visual>
      <collision name="c"><geometry><box><size>{WALL_THICK} {2 * WALL_HALF} {2 * WALL_HALF}</size></box></geometry>
      </collision></link></model>"""


def scene(kind: str, yaw: float, lens: str = "") -> tuple[Any, CameraSensor]:
    pw, ents = build(sdf_world(wall(yaw) + rig(kind, yaw, lens=lens)))
    entity = ents["rig"]
    s = next(entity.model.sensors())
    return pw, CameraSensor(Camera(entity, s, np.random.default_rng(0), (-0.5, 0.1, -0.9), pw.all_flat_planes))


def wall_mask(info: dict, margin_px: float) -> tuple[np.ndarray, np.ndarray]:
    """Pixels surely on the wall and surely beside it, from camera_info alone: the wall's edges projected
    through K (optical frame: u = cx + fx * left-right offset / depth)."""
    k = info["intrinsics"]["k"]
    fx, cx, fy, cy = k[0], k[2], k[4], k[5]
    u, v = np.meshgrid(np.arange(W) + 0.5, np.arange(H) + 0.5)
    half_u, top_v, bottom_v = fx * WALL_HALF / FACE, cy - fy * (2 * WALL_HALF - CAM_Z) / FACE, cy + fy * CAM_Z / FACE
    du = np.abs(u - cx)
    inside = (du < half_u - margin_px) & (v > top_v + margin_px) & (v < bottom_v - margin_px)
    outside = (du > half_u + margin_px) | (v < top_v - margin_px) | (v > bottom_v + margin_px)
    return inside, outside


# An off-centre lens (<lens><intrinsics>) moves the wall in the image; camera_info's K says where.
OFF_CENTRE = "<lens><intrinsics><fx>120</fx><fy>120</fy><cx>70</cx><cy>50</cy><s>0</s></intrinsics></lens>"


@pytest.mark.parametrize(("yaw", "lens"), [(0.0, ""), (2.0, ""), (0.0, OFF_CENTRE)])
def test_rgbd_sees_the_wall_where_it_is(yaw: float, lens: str) -> None:
    pw, cam = scene("rgbd_camera", yaw, lens)
    try:
        msgs = cam.messages(1_500_000_000, {"image", "depth_image", "points", "camera_info"})
        assert cam.frames == 1  # one render fed all four
        info, img, dep, pts = msgs["camera_info"], msgs["image"], msgs["depth_image"], msgs["points"]
        for m in msgs.values():
            assert m["header"]["stamp"] == {"sec": 1, "nsec": 500_000_000}
            assert m["header"]["data"] == [{"key": "frame_id", "value": ["rig::l::eye"]}]
        assert (img["width"], img["height"], img["step"], img["pixel_format_type"]) == (W, H, 3 * W, "RGB_INT8")
        assert (dep["step"], dep["pixel_format_type"]) == (4 * W, "R_FLOAT32")
        rgb = np.frombuffer(img["data"], dtype=np.uint8).reshape(H, W, 3)
        d = np.frombuffer(dep["data"], dtype="<f4").reshape(H, W)
        inside, outside = wall_mask(info, margin_px=1.5)
        assert inside.sum() > 2000 and outside.sum() > 5000
        assert np.allclose(d[inside], FACE, atol=0.01)  # the true distance to the face
        assert np.all(np.isposinf(d[outside]))  # nothing there within the far clip: +inf, as Gazebo
        assert np.all(rgb[inside][:, 0] > 2 * rgb[inside][:, 1].astype(int))  # red

        xyz, colours = unpack_points(pts["data"])
        xyz, colours = xyz.reshape(H, W, 3), colours.reshape(H, W, 3)
        assert (pts["width"], pts["height"], pts["row_step"]) == (W, H, 24 * W)
        assert np.array_equal(colours, rgb)  # the points carry the image's colours
        face = xyz[inside]
        # In the sensor frame (x forward, y left, z up) whatever the camera's yaw in the world.
        assert np.allclose(face[:, 0], FACE, atol=0.01)
        assert np.all(np.abs(face[:, 1]) < WALL_HALF) and np.all((face[:, 2] > -CAM_Z) & (face[:, 2] < CAM_Z))
        # ... and where the wall is in the world once the sensor's pose is applied.
        pose = cam.camera.pose()
        world = np.array([pose.transform_point(p.tolist()) for p in face[::97]])
        normal = np.array([math.cos(yaw), math.sin(yaw)])
        assert np.allclose(world[:, :2] @ normal, FACE, atol=0.01)
        assert np.all((world[:, 2] > 0) & (world[:, 2] < 2 * WALL_HALF))
        assert np.all(np.isposinf(xyz[outside]))
    finally:
        pw.close()


def test_depth_camera_points_are_grey_by_depth() -> None:
    pw, cam = scene("depth_camera", 0.0)
    try:
        msgs = cam.messages(0, {"depth_image", "points"})
        d = np.frombuffer(msgs["depth_image"]["data"], dtype="<f4").reshape(H, W)
        xyz, colours = unpack_points(msgs["points"]["data"])
        assert np.array_equal(xyz[:, 0].reshape(H, W), d)
        finite = np.isfinite(d).ravel()
        assert finite.any() and np.all(colours[finite, 0] == colours[finite, 1])  # grey
        assert np.all(colours[~finite] == 0)
    finally:
        pw.close()


class Sink:
    """A publisher end: whether someone listens, and what was published."""

    def __init__(self, matched: bool = False) -> None:
        self.matched = matched
        self.got: list[dict] = []

    def publish(self, msg: dict) -> None:
        self.got.append(msg)


def test_rendering_follows_demand() -> None:
    pw, cam = scene("rgbd_camera", 0.0)
    try:
        sinks = {n: Sink() for n in ("image", "depth_image", "points", "camera_info")}
        job = CameraTask(cam, sinks, RenderRate(100_000_000, 1_000_000), lambda: 1.0, lambda _t: None)
        job(0)
        assert cam.frames == 0 and not any(s.got for s in sinks.values())  # nobody: nothing at all
        sinks["camera_info"].matched = True
        job(100_000_000)
        assert cam.frames == 0 and len(sinks["camera_info"].got) == 1  # camera_info needs no render
        sinks["points"].matched = sinks["image"].matched = True
        for t in (2, 3, 4):
            job(t * 100_000_000)
        assert cam.frames == 3  # one render per tick for both outputs
        assert len(sinks["points"].got) == len(sinks["image"].got) == 3 and not sinks["depth_image"].got
    finally:
        pw.close()


def test_too_slow_a_camera_lowers_its_rate_and_says_so_once() -> None:
    pw, cam = scene("rgbd_camera", 0.0)
    try:
        said: list[str] = []
        sinks = {"image": Sink(matched=True)}
        rate = RenderRate(10_000_000, 1_000_000, budget=1e-6)  # no render fits: forces the decision
        job = CameraTask(cam, sinks, rate, lambda: 1.0, said.append)
        job.task = Task("cam", 10_000_000, job, 0, 1)
        for t in range(6):
            job(t * 10_000_000)
        assert job.task.period_ns > 10_000_000 and job.task.period_ns % 1_000_000 == 0
        assert len(said) == 1 and "rig::l::eye" in said[0] and "100 Hz" in said[0]
    finally:
        pw.close()


def test_optical_frame_id_relabels_only() -> None:
    extra_cam = "<optical_frame_id>eye_optical</optical_frame_id>"
    body = wall(0.0) + rig("rgbd_camera", 0.0).replace("</clip></camera>", "</clip>" + extra_cam + "</camera>")
    pw, ents = build(sdf_world(body))
    try:
        s = next(ents["rig"].model.sensors())
        cam = CameraSensor(Camera(ents["rig"], s, np.random.default_rng(0), (0.0, 0.0, -1.0)))
        msgs = cam.messages(0, {"points", "camera_info"})
        assert {m["header"]["data"][0]["value"][0] for m in msgs.values()} == {"eye_optical"}
        xyz, _ = unpack_points(msgs["points"]["data"])
        assert np.nanmax(np.where(np.isfinite(xyz[:, 0]), xyz[:, 0], np.nan)) == pytest.approx(FACE, abs=0.01)
    finally:
        pw.close()


def test_every_output_reaches_ros_through_the_bridge_conversions() -> None:
    """The sim side of the contract with the bridge: each output, encoded for the gz bus, converts to its ROS
    type and survives CDR (rosbags' Jazzy typestore) with the frame id and layout a ROS user expects."""
    from diffctl.bridge import type_pairs
    from diffctl.bus import gz
    from diffctl.interfaces import types

    pw, cam = scene("rgbd_camera", 0.0)
    try:
        msgs = cam.messages(1_000_000_000, {"image", "depth_image", "points", "camera_info"})
        ros_types = {
            "image": ("sensor_msgs/msg/Image", "gz.msgs.Image"),
            "depth_image": ("sensor_msgs/msg/Image", "gz.msgs.Image"),
            "points": ("sensor_msgs/msg/PointCloud2", "gz.msgs.PointCloudPacked"),
            "camera_info": ("sensor_msgs/msg/CameraInfo", "gz.msgs.CameraInfo"),
        }
        ros = {}
        for name, (ros_type, gz_type) in ros_types.items():
            pair = type_pairs.lookup(ros_type, gz_type)
            assert pair is not None
            _, fields = gz.decode(gz.encode(gz_type, msgs[name]), gz_type)
            ros[name] = types.deserialize(types.serialize(pair.convert_to_ros(fields), ros_type), ros_type)
        assert {m.header.frame_id for m in ros.values()} == {"rig/l/eye"}
        assert (ros["image"].encoding, ros["depth_image"].encoding) == ("rgb8", "32FC1")
        d = np.frombuffer(bytes(ros["depth_image"].data), dtype="<f4").reshape(H, W)
        assert d[H // 2, W // 2] == pytest.approx(FACE, abs=0.01)
        cloud = ros["points"]
        assert [(f.name, f.offset, f.datatype) for f in cloud.fields] == [
            ("x", 0, 7),  # sensor_msgs/PointField FLOAT32
            ("y", 4, 7),
            ("z", 8, 7),
            ("rgb", 16, 7),
        ]
        assert (cloud.point_step, cloud.row_step, len(cloud.data)) == (24, 24 * W, 24 * W * H)
        info = ros["camera_info"]
        assert info.distortion_model == "plumb_bob" and info.k[2] == W / 2 and info.k[5] == H / 2
    finally:
        pw.close()


def test_depth_clip_and_distortion_of_an_rgbd_camera_as_gazebo() -> None:
    lens = (
        "<distortion><k1>-0.2</k1><k2>0.05</k2><p1>0.001</p1><p2>0.002</p2><k3>0.01</k3></distortion>"
        "<depth_camera><clip><near>0.2</near><far>1.5</far></clip></depth_camera>"
    )
    pw, cam = scene("rgbd_camera", 0.0, lens)
    try:
        msgs = cam.messages(0, {"depth_image", "points", "camera_info", "image"})
        d = np.frombuffer(msgs["depth_image"]["data"], dtype="<f4")
        assert np.all(np.isposinf(d))  # the wall at 1.9 m is beyond the depth clip's 1.5 m
        xyz, _ = unpack_points(msgs["points"]["data"])
        assert np.all(np.isposinf(xyz))
        rgb = np.frombuffer(msgs["image"]["data"], dtype=np.uint8).reshape(H, W, 3)
        assert rgb[H // 2, W // 2, 0] > 2 * rgb[H // 2, W // 2, 1]  # the colour image still sees it
        # Gazebo does not distort depth or rgbd images, and reports the SDF's coefficients as they are.
        assert msgs["camera_info"]["distortion"]["k"] == [-0.2, 0.05, 0.001, 0.002, 0.01] and not cam.notes
    finally:
        pw.close()


def test_a_plain_cameras_distortion_is_reported_as_not_simulated() -> None:
    pw, cam = scene("camera", 0.0, "<distortion><k1>-0.2</k1></distortion>")
    try:
        assert cam.messages(0, {"camera_info"})["camera_info"]["distortion"]["k"] == [0.0] * 5
        assert len(cam.notes) == 1 and "<distortion>" in cam.notes[0]
    finally:
        pw.close()
