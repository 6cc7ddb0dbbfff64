"""One sim-side sample per supported type pair, in the layouts of diffctl/bus/gz.py (shared by the tests)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from diffctl.bus import gz

H = gz.header(12_500_000_000, frame_id="robot::base_link", child_frame_id="robot::odom_child")

# An RGBD-style cloud (gz-msgs InitPointCloudPacked layout): x, y, z at 0/4/8, rgb at 16, 24-byte points.
CLOUD_DTYPE = np.dtype(
    {"names": ["x", "y", "z", "rgb"], "formats": ["<f4", "<f4", "<f4", "<f4"], "offsets": [0, 4, 8, 16], "itemsize": 24}
)
CLOUD = np.zeros(6, dtype=CLOUD_DTYPE)
CLOUD["x"], CLOUD["y"], CLOUD["z"] = np.arange(6) + 1.0, np.arange(6) * -0.5, 0.25
CLOUD["rgb"] = np.frombuffer(bytes([30, 20, 10, 0] * 6), dtype="<f4")  # B, G, R in little-endian order


def plain(value: Any) -> Any:
    """A gz dict with its numpy arrays as lists, so two dicts compare with ==."""
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    return value


# One sim-side sample per pair, in the layouts of diffctl/bus/gz.py, and what the ROS side must see.
WRENCH = {"force": {"x": 1.0, "y": 2.0, "z": 3.0}, "torque": {"x": 0.1, "y": 0.2, "z": 0.3}}
JOINT_WRENCH = {
    "header": gz.header(9, frame_id="j"),
    "body_1_name": "robot::wheel",
    "body_1_id": 11,
    "body_2_name": "ground",
    "body_2_id": 2,
    "body_1_wrench": WRENCH,
    "body_2_wrench": WRENCH,
}
CONTACT = {
    "collision1": {"id": 3, "name": "robot::bumper::collision", "type": "COLLISION"},
    "collision2": {"id": 3, "name": "robot::bumper::collision", "type": "COLLISION"},
    "position": [{"x": 1.0, "y": 0.0, "z": 0.1}],
    "normal": [{"x": -1.0, "y": 0.0, "z": 0.0}],
    "depth": [0.001],
    "wrench": [JOINT_WRENCH],
}

TRACK = {
    "header": gz.header(2, frame_id="gui"),
    "name": "robot",
    "id": 8,
    "inherit_orientation": True,
    "min_dist": 0.5,
    "max_dist": 10.0,
    "static": False,
    "use_model_frame": True,
    "xyz": {"x": -2.0, "y": 0.0, "z": 1.0},
    "inherit_yaw": True,
}

BOX_2D = {
    "header": gz.header(3, frame_id="camera::link"),
    "box": {"min_corner": {"x": 10.0, "y": 20.0}, "max_corner": {"x": 50.0, "y": 80.0}},
    "label": 7,
}
BOX_3D = {
    "header": gz.header(4, frame_id="camera::link"),
    "box": {
        "center": {"x": 1.0, "y": -2.0, "z": 0.5},
        "boxsize": {"x": 0.4, "y": 0.6, "z": 1.2},
        "orientation": {"x": 0.0, "y": 0.0, "z": math.sin(0.25), "w": math.cos(0.25)},
    },
    "label": 3,
}

GZ_SAMPLES: dict[tuple[str, str], dict] = {
    ("actuator_msgs/msg/Actuators", "gz.msgs.Actuators"): {
        "header": H,
        "position": [0.5, -1.0],
        "velocity": [100.0, 200.0, 300.0, 400.0],
        "normalized": [],
    },
    ("gps_msgs/msg/GPSFix", "gz.msgs.NavSat"): {
        "header": gz.header(9),
        "latitude_deg": -22.9,
        "longitude_deg": -43.2,
        "altitude": 12.5,
        "velocity_east": 3.0,
        "velocity_north": 4.0,
        "velocity_up": -0.5,
        "frame_id": "robot::gps_link",
    },
    ("vision_msgs/msg/Detection2D", "gz.msgs.AnnotatedAxisAligned2DBox"): BOX_2D,
    ("vision_msgs/msg/Detection2DArray", "gz.msgs.AnnotatedAxisAligned2DBox_V"): {
        "header": H,
        "annotated_box": [BOX_2D, {**BOX_2D, "label": 0}],
    },
    ("vision_msgs/msg/Detection3D", "gz.msgs.AnnotatedOriented3DBox"): BOX_3D,
    ("vision_msgs/msg/Detection3DArray", "gz.msgs.AnnotatedOriented3DBox_V"): {"header": H, "annotated_box": [BOX_3D]},
    ("rosgraph_msgs/msg/Clock", "gz.msgs.Clock"): {
        "header": gz.header(7),
        "sim": {"sec": 3, "nsec": 250},
        "real": {"sec": 9, "nsec": 1},
    },
    ("geometry_msgs/msg/Twist", "gz.msgs.Twist"): {"header": H, "linear": {"x": 0.5}, "angular": {"z": -0.25}},
    ("geometry_msgs/msg/TwistStamped", "gz.msgs.Twist"): {"header": H, "linear": {"x": 0.5}, "angular": {"z": -0.25}},
    ("nav_msgs/msg/Odometry", "gz.msgs.Odometry"): {
        "header": gz.header(12_500_000_000, frame_id="odom", child_frame_id="base_link"),
        "pose": {"position": {"x": 1.0, "y": 2.0}, "orientation": {"z": 0.6, "w": 0.8}},
        "twist": {"linear": {"x": 0.3}, "angular": {"z": 0.1}},
    },
    ("sensor_msgs/msg/JointState", "gz.msgs.Model"): {
        "header": gz.header(5, frame_id=""),
        "name": "robot",
        "joint": [
            {"name": "left", "axis1": {"position": 1.5, "velocity": 2.0, "force": 0.1}},
            {"name": "right", "axis1": {"position": -1.0, "velocity": -2.0}},
        ],
    },
    ("tf2_msgs/msg/TFMessage", "gz.msgs.Pose_V"): {
        "header": gz.header(42),
        "pose": [
            {
                "name": "base_link",
                "header": gz.header(42, "odom", "base_link"),
                "position": {"x": 1.0},
                "orientation": {"w": 1.0},
            },
            {
                "name": "robot::lidar_link",
                "header": {"data": [{"key": "frame_id", "value": ["robot::base_link"]}]},
                "position": {"z": 0.2},
                "orientation": {"x": 0.0, "w": 1.0},
            },
        ],
    },
    ("sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan"): {
        "header": gz.header(99, frame_id="x"),
        "frame": "robot::lidar_link",
        "angle_min": -math.pi,
        "angle_max": math.pi,
        "angle_step": math.pi / 2,
        "range_min": 0.1,
        "range_max": 10.0,
        "count": 4,
        "vertical_count": 1,
        # Packed as the sim packs them: numpy arrays travel as raw little-endian bytes.
        "ranges": np.array([1.0, 2.0, math.inf, 0.5]),
        "intensities": np.array([0.0, 1.0, 0.0, 1.0], dtype=np.float32),
    },
    ("sensor_msgs/msg/Imu", "gz.msgs.IMU"): {
        "header": gz.header(3, frame_id="imu_link"),
        "entity_name": "imu_link",
        "orientation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0},
        "angular_velocity": {"z": 0.5},
        "linear_acceleration": {"z": 9.81},
        "angular_velocity_covariance": {"data": [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01]},
        "linear_acceleration_covariance": {"data": [0.5]},  # not 9 elements: ignored, as upstream does
    },
    ("sensor_msgs/msg/Image", "gz.msgs.Image"): {
        "header": gz.header(4, frame_id="camera_link"),
        "width": 2,
        "height": 2,
        "step": 6,
        "pixel_format_type": "RGB_INT8",
        "data": bytes(range(12)),
    },
    ("sensor_msgs/msg/CameraInfo", "gz.msgs.CameraInfo"): {
        "header": gz.header(4, frame_id="robot::camera_link::camera"),
        "width": 320,
        "height": 240,
        "distortion": {"model": "PLUMB_BOB", "k": [-0.25, 0.12, -0.00028, -5e-05, 0.0]},
        "intrinsics": {"k": [277.19, 0.0, 160.5, 0.0, 277.19, 120.5, 0.0, 0.0, 1.0]},
        "projection": {"p": [277.19, 0.0, 160.5, -19.4, 0.0, 277.19, 120.5, 0.0, 0.0, 0.0, 1.0, 0.0]},
        "rectification_matrix": [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
    },
    ("sensor_msgs/msg/PointCloud2", "gz.msgs.PointCloudPacked"): {
        "header": gz.header(6, frame_id="robot::camera_link::rgbd"),
        "field": [
            {"name": "x", "offset": 0, "datatype": "FLOAT32", "count": 1},
            {"name": "y", "offset": 4, "datatype": "FLOAT32", "count": 1},
            {"name": "z", "offset": 8, "datatype": "FLOAT32", "count": 1},
            {"name": "rgb", "offset": 16, "datatype": "FLOAT32", "count": 1},
        ],
        "height": 2,
        "width": 3,
        "is_bigendian": False,
        "point_step": 24,
        "row_step": 72,
        "data": CLOUD.tobytes(),
        "is_dense": True,
    },
    ("sensor_msgs/msg/NavSatFix", "gz.msgs.NavSat"): {
        "header": gz.header(9),
        "latitude_deg": 47.3977,
        "longitude_deg": 8.5456,
        "altitude": 488.1,
        "frame_id": "robot::gps_link",
        "velocity_east": 0.2,
    },
    ("builtin_interfaces/msg/Time", "gz.msgs.Time"): {"sec": 12, "nsec": 500},
    ("std_msgs/msg/Header", "gz.msgs.Header"): gz.header(3_000_000_007, frame_id="robot::base_link"),
    ("std_msgs/msg/ColorRGBA", "gz.msgs.Color"): {"r": 0.25, "g": 0.5, "b": 0.75, "a": 1.0},
    ("geometry_msgs/msg/Quaternion", "gz.msgs.Quaternion"): {"x": 0.0, "y": 0.0, "z": 0.6, "w": 0.8},
    ("sensor_msgs/msg/Joy", "gz.msgs.Joy"): {"header": H, "axes": [0.5, -1.0], "buttons": [0, 1, 1]},
    ("trajectory_msgs/msg/JointTrajectory", "gz.msgs.JointTrajectory"): {
        "header": H,
        "joint_names": ["shoulder", "elbow"],
        "points": [
            {
                "positions": [0.1, 0.2],
                "velocities": [0.0, 0.5],
                "accelerations": [],
                "effort": [],
                "time_from_start": {"sec": 1, "nsec": 250_000_000},
            }
        ],
    },
    ("rcl_interfaces/msg/ParameterValue", "gz.msgs.Any"): {"type": "DOUBLE", "double_value": 2.5},
    ("geometry_msgs/msg/PoseWithCovariance", "gz.msgs.PoseWithCovariance"): {
        "pose": {"position": {"x": 1.0, "y": 2.0, "z": 0.0}, "orientation": {"x": 0, "y": 0, "z": 0.6, "w": 0.8}},
        "covariance": {"data": [float(i) for i in range(36)]},
    },
    ("geometry_msgs/msg/PoseWithCovarianceStamped", "gz.msgs.PoseWithCovariance"): {
        "pose": {
            "header": H,
            "position": {"x": 1.0, "y": 2.0, "z": 0.0},
            "orientation": {"x": 0, "y": 0, "z": 0.6, "w": 0.8},
        },
        "covariance": {"data": [0.5] * 36},
    },
    ("geometry_msgs/msg/TwistWithCovariance", "gz.msgs.TwistWithCovariance"): {
        "twist": {"linear": {"x": 0.3, "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": 0.2}},
        "covariance": {"data": [float(i) / 10 for i in range(36)]},
    },
    ("geometry_msgs/msg/TwistWithCovarianceStamped", "gz.msgs.TwistWithCovariance"): {
        "twist": {"header": H, "linear": {"x": 0.3, "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": 0.2}},
        "covariance": {"data": [0.25] * 36},
    },
    ("nav_msgs/msg/Odometry", "gz.msgs.OdometryWithCovariance"): {
        "header": H,
        "pose_with_covariance": {
            "pose": {"position": {"x": 1.0, "y": 2.0, "z": 0.0}, "orientation": {"x": 0, "y": 0, "z": 0.6, "w": 0.8}},
            "covariance": {"data": [0.01] * 36},
        },
        "twist_with_covariance": {
            "twist": {"linear": {"x": 0.3, "y": 0.0, "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": 0.2}},
            "covariance": {"data": [0.02] * 36},
        },
    },
    ("ros_gz_interfaces/msg/Altimeter", "gz.msgs.Altimeter"): {
        "header": H,
        "vertical_position": 12.5,
        "vertical_velocity": -0.25,
        "vertical_reference": 100.0,
    },
    ("ros_gz_interfaces/msg/Entity", "gz.msgs.Entity"): {"id": 42, "name": "robot::base_link", "type": "LINK"},
    ("ros_gz_interfaces/msg/EntityWrench", "gz.msgs.EntityWrench"): {
        "header": H,
        "entity": {"id": 7, "name": "box", "type": "MODEL"},
        "wrench": {"force": {"x": 1.0, "y": 0.0, "z": 9.8}, "torque": {"x": 0.0, "y": 0.0, "z": 0.5}},
    },
    ("ros_gz_interfaces/msg/JointWrench", "gz.msgs.JointWrench"): JOINT_WRENCH,
    ("ros_gz_interfaces/msg/Contact", "gz.msgs.Contact"): CONTACT,
    ("ros_gz_interfaces/msg/Contacts", "gz.msgs.Contacts"): {"header": H, "contact": [CONTACT, CONTACT]},
    ("ros_gz_interfaces/msg/Dataframe", "gz.msgs.Dataframe"): {
        "header": {**gz.header(5, frame_id="radio"), "data": [{"key": "rssi", "value": ["-67.500000"]}]},
        "src_address": "addr1",
        "dst_address": "addr2",
        "data": b"\x00\x01hello",
    },
    ("ros_gz_interfaces/msg/Float32Array", "gz.msgs.Float_V"): {"data": [0.5, -1.25, 3.0]},
    ("ros_gz_interfaces/msg/StringVec", "gz.msgs.StringMsg_V"): {"header": H, "data": ["a", "b c"]},
    ("ros_gz_interfaces/msg/ParamVec", "gz.msgs.Param"): {
        "header": H,
        "params": {"gain": {"type": "DOUBLE", "double_value": 0.5}, "name": {"type": "STRING", "string_value": "x"}},
    },
    ("ros_gz_interfaces/msg/ParamVec", "gz.msgs.Param_V"): {
        "header": H,
        "param": [{"params": {"on": {"type": "BOOLEAN", "bool_value": True}, "n": {"type": "INT32", "int_value": 3}}}],
    },
    ("ros_gz_interfaces/msg/Light", "gz.msgs.Light"): {
        "header": H,
        "name": "lamp",
        "type": "SPOT",
        "pose": {"position": {"x": 0.0, "y": 0.0, "z": 3.0}, "orientation": {"x": 0, "y": 0, "z": 0, "w": 1.0}},
        "diffuse": {"r": 1.0, "g": 0.5, "b": 0.25, "a": 1.0},
        "specular": {"r": 0.5, "g": 0.5, "b": 0.5, "a": 1.0},
        "attenuation_constant": 0.5,
        "attenuation_linear": 0.25,
        "attenuation_quadratic": 0.125,
        "direction": {"x": 0.0, "y": 0.0, "z": -1.0},
        "range": 20.0,
        "cast_shadows": True,
        "spot_inner_angle": 0.5,
        "spot_outer_angle": 1.0,
        "spot_falloff": 0.75,
        "id": 4,
        "parent_id": 1,
        "intensity": 2.0,
    },
    ("ros_gz_interfaces/msg/MaterialColor", "gz.msgs.MaterialColor"): {
        "header": H,
        "entity": {"id": 0, "name": "box::link::visual", "type": "VISUAL"},
        "ambient": {"r": 0.25, "g": 0.25, "b": 0.25, "a": 1.0},
        "diffuse": {"r": 1.0, "g": 0.0, "b": 0.0, "a": 1.0},
        "specular": {"r": 0.5, "g": 0.5, "b": 0.5, "a": 1.0},
        "emissive": {"r": 0.0, "g": 0.0, "b": 0.0, "a": 1.0},
        "shininess": 8.0,
        "entity_match": "ALL",
    },
    ("ros_gz_interfaces/msg/SensorNoise", "gz.msgs.SensorNoise"): {
        "header": H,
        "type": "GAUSSIAN_QUANTIZED",
        "mean": 0.0,
        "stddev": 0.01,
        "bias_mean": 0.001,
        "bias_stddev": 0.0005,
        "precision": 0.1,
        "dynamic_bias_stddev": 0.002,
    },
    ("ros_gz_interfaces/msg/TrackVisual", "gz.msgs.TrackVisual"): TRACK,
    ("ros_gz_interfaces/msg/GuiCamera", "gz.msgs.GUICamera"): {
        "header": H,
        "name": "user_camera",
        "view_controller": "orbit",
        "pose": {"position": {"x": -6.0, "y": 0.0, "z": 6.0}, "orientation": {"x": 0, "y": 0.38, "z": 0, "w": 0.92}},
        "track": TRACK,
        "projection_type": "perspective",
    },
    ("ros_gz_interfaces/msg/VideoRecord", "gz.msgs.VideoRecord"): {
        "header": H,
        "start": True,
        "stop": False,
        "format": "mp4",
        "save_filename": "/tmp/run.mp4",
    },
    ("sensor_msgs/msg/BatteryState", "gz.msgs.BatteryState"): {
        "header": gz.header(12, frame_id="robot::battery"),
        "voltage": 12.5,
        "current": -1.25,
        "charge": 1.5,
        "capacity": 2.0,
        "percentage": 0.75,
        "power_supply_status": "DISCHARGING",
    },
    ("sensor_msgs/msg/MagneticField", "gz.msgs.Magnetometer"): {
        "header": gz.header(10, frame_id="mag_link"),
        "field_tesla": {"x": 2.2e-05, "y": 0.0, "z": -4.3e-05},
    },
    ("sensor_msgs/msg/FluidPressure", "gz.msgs.FluidPressure"): {
        "header": gz.header(11, frame_id="baro_link"),
        "pressure": 101325.0,
        "variance": 0.25,
    },
    ("std_msgs/msg/Empty", "gz.msgs.Empty"): {},
    ("geometry_msgs/msg/Pose", "gz.msgs.Pose"): {
        "name": "robot",
        "position": {"x": 1.0, "y": -2.0, "z": 0.1},
        "orientation": {"z": 0.6, "w": 0.8},
    },
    ("geometry_msgs/msg/PoseStamped", "gz.msgs.Pose"): {
        "header": gz.header(8, frame_id="world"),
        "name": "robot",
        "position": {"x": 1.0},
        "orientation": {"w": 1.0},
    },
    ("geometry_msgs/msg/PoseArray", "gz.msgs.Pose_V"): {
        "header": gz.header(13, frame_id="map"),
        "pose": [
            {"name": "a", "position": {"x": 1.0, "y": 2.0}, "orientation": {"w": 1.0}},
            {"name": "b", "position": {"z": -1.0}, "orientation": {"z": 0.6, "w": 0.8}},
        ],
    },
    ("geometry_msgs/msg/Transform", "gz.msgs.Pose"): {
        "position": {"x": 0.1, "y": 0.2, "z": 0.3},
        "orientation": {"x": 0.0, "y": 0.0, "z": 0.6, "w": 0.8},
    },
    ("geometry_msgs/msg/TransformStamped", "gz.msgs.Pose"): {
        "header": gz.header(14, "robot::base_link", "robot::lidar_link"),
        "name": "lidar_link",
        "position": {"z": 0.2},
        "orientation": {"w": 1.0},
    },
    ("geometry_msgs/msg/Vector3", "gz.msgs.Vector3d"): {"x": 1.5, "y": -2.5, "z": 3.5},
    ("geometry_msgs/msg/Point", "gz.msgs.Vector3d"): {"x": -1.0, "z": 0.25},
    ("geometry_msgs/msg/Wrench", "gz.msgs.Wrench"): {"force": {"x": 10.0}, "torque": {"z": -0.5}},
    ("geometry_msgs/msg/WrenchStamped", "gz.msgs.Wrench"): {
        "header": gz.header(15, frame_id="wheel"),
        "force": {"y": 2.0},
        "torque": {"x": 0.25},
    },
    ("std_msgs/msg/UInt32", "gz.msgs.UInt32"): {"data": 4_000_000_000},
    ("std_msgs/msg/Float64", "gz.msgs.Double"): {"data": 2.5},
    ("std_msgs/msg/Float32", "gz.msgs.Float"): {"data": 1.5},
    ("std_msgs/msg/Bool", "gz.msgs.Boolean"): {"data": True},
    ("std_msgs/msg/Int32", "gz.msgs.Int32"): {"data": -7},
    ("std_msgs/msg/String", "gz.msgs.StringMsg"): {"data": "hello"},
}


def same(a: object, b: object, rel_tol: float = 0.0) -> bool:
    # == but NaN equals NaN (ros_gz_bridge fills some fields with NaN, e.g. BatteryState.design_capacity);
    # rel_tol > 0 for pairs whose conversion goes through trigonometry (GPSFix's speed and track).
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    if rel_tol and isinstance(a, float) and isinstance(b, float):
        return math.isclose(a, b, rel_tol=rel_tol, abs_tol=rel_tol)
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k], rel_tol) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(same(x, y, rel_tol) for x, y in zip(a, b, strict=True))
    return bool(np.all(a == b)) if isinstance(a, np.ndarray) or isinstance(b, np.ndarray) else a == b
