"""One sim-side sample per supported type pair, in the layouts of diffctl/bus/gz.py (shared by the tests)."""

from __future__ import annotations

import base64
import math

from diffctl.bus import gz

H = gz.header(12_500_000_000, frame_id="robot::base_link", child_frame_id="robot::odom_child")

# One sim-side sample per pair, in the layouts of diffctl/bus/gz.py, and what the ROS side must see.
GZ_SAMPLES: dict[tuple[str, str], dict] = {
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
        "ranges": [1.0, 2.0, math.inf, 0.5],
        "intensities": [0.0, 1.0, 0.0, 1.0],
    },
    ("sensor_msgs/msg/Imu", "gz.msgs.IMU"): {
        "header": gz.header(3, frame_id="imu_link"),
        "entity_name": "imu_link",
        "orientation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0},
        "angular_velocity": {"z": 0.5},
        "linear_acceleration": {"z": 9.81},
    },
    ("sensor_msgs/msg/Image", "gz.msgs.Image"): {
        "header": gz.header(4, frame_id="camera_link"),
        "width": 2,
        "height": 2,
        "step": 6,
        "pixel_format_type": "RGB_INT8",
        "data": base64.b64encode(bytes(range(12))).decode(),
    },
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
    ("std_msgs/msg/Float64", "gz.msgs.Double"): {"data": 2.5},
    ("std_msgs/msg/Float32", "gz.msgs.Float"): {"data": 1.5},
    ("std_msgs/msg/Bool", "gz.msgs.Boolean"): {"data": True},
    ("std_msgs/msg/Int32", "gz.msgs.Int32"): {"data": -7},
    ("std_msgs/msg/String", "gz.msgs.StringMsg"): {"data": "hello"},
}
