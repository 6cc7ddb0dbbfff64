"""Which gz topics a sensor publishes on, named as Gazebo Harmonic names them.

The base topic T is `<topic>`, else `/world/<w>/model/<m>/link/<l>/sensor/<s>` plus a per-type suffix
(gz-sim RenderUtil.cc, Imu.cc). From T: camera → T (Image) and its CameraInfo on `<camera_info_topic>`, else
T with the last segment replaced by `camera_info`; depth_camera → T (depth Image), T/points and CameraInfo by
the camera rule; rgbd_camera → T/image, T/depth_image, T/points, T/camera_info; lidar → T and T/points;
imu, air_pressure, navsat, magnetometer → T.
"""

from __future__ import annotations

from dataclasses import dataclass

from diffctl.description.model import Sensor

DEFAULT_SUFFIX = {
    "camera": "/image",
    "depth_camera": "/depth_image",
    "rgbd_camera": "",
    "lidar": "/scan",
    "imu": "/imu",
    "air_pressure": "/air_pressure",
    "navsat": "/navsat",
    "magnetometer": "/magnetometer",
}

IMAGE, DEPTH, POINTS, INFO, SCAN, IMU = "image", "depth_image", "points", "camera_info", "scan", "imu"
PRESSURE, NAVSAT, MAGNETIC = "air_pressure", "navsat", "magnetometer"


@dataclass(frozen=True)
class Output:
    name: str  # one of the constants above
    topic: str
    gz_type: str


def scoped_path(model: str, link: str) -> str:
    """`model/<m>/link/<l>`, nested models (`inner::wheel`) as `model/<m>/model/inner/link/wheel`."""
    *inner, leaf = link.split("::")
    return "/".join([f"model/{model}", *(f"model/{m}" for m in inner), f"link/{leaf}"])


def base_topic(sensor: Sensor, world: str, model: str) -> str:
    if sensor.topic:
        return sensor.topic
    return f"/world/{world}/{scoped_path(model, sensor.link)}/sensor/{sensor.name}{DEFAULT_SUFFIX[sensor.type]}"


def sibling_camera_info(image_topic: str) -> str:
    """T with its last segment replaced by `camera_info` (CameraSensor::AdvertiseInfo); `/camera` → `/camera_info`."""
    parts = [p for p in image_topic.split("/") if p][:-1]
    return "/" + "/".join([*parts, "camera_info"])


def outputs(sensor: Sensor, base: str) -> tuple[Output, ...]:
    kind = sensor.type
    if kind == "lidar":
        return (Output(SCAN, base, "gz.msgs.LaserScan"), Output(POINTS, base + "/points", "gz.msgs.PointCloudPacked"))
    if kind == "imu":
        return (Output(IMU, base, "gz.msgs.IMU"),)
    if kind == "air_pressure":
        return (Output(PRESSURE, base, "gz.msgs.FluidPressure"),)
    if kind == "navsat":
        return (Output(NAVSAT, base, "gz.msgs.NavSat"),)
    if kind == "magnetometer":
        return (Output(MAGNETIC, base, "gz.msgs.Magnetometer"),)
    if kind == "rgbd_camera":
        return (
            Output(IMAGE, base + "/image", "gz.msgs.Image"),
            Output(DEPTH, base + "/depth_image", "gz.msgs.Image"),
            Output(POINTS, base + "/points", "gz.msgs.PointCloudPacked"),
            Output(INFO, base + "/camera_info", "gz.msgs.CameraInfo"),
        )
    assert sensor.camera is not None
    info = Output(INFO, sensor.camera.camera_info_topic or sibling_camera_info(base), "gz.msgs.CameraInfo")
    if kind == "depth_camera":
        return (
            Output(DEPTH, base, "gz.msgs.Image"),
            Output(POINTS, base + "/points", "gz.msgs.PointCloudPacked"),
            info,
        )
    return (Output(IMAGE, base, "gz.msgs.Image"), info)
