"""A stand-in for sim + controllers that feeds the visualizer in tests: a unicycle driven by TwistStamped.

Publishes /robot_description (the repo's SDF, latched), /tf_static from its fixed joints, /tf
odom→base_footprint, /diffbot_base_controller/odom, /joint_states, /clock and a /scan of a square room,
plus a small /camera/image_raw while someone subscribes. Prints "ready" once everything is declared.
Usage: python tests/viz/fake_robot.py [SDF]
"""

from __future__ import annotations

import math
import sys
import threading
import time
from pathlib import Path

import numpy as np

from diffctl.description import sdf_loader
from diffctl.interfaces import types
from tests.probe import Probe

REPO = Path(__file__).resolve().parents[2]
ROOM_HALF_M = 3.0
RATE_HZ = 50.0


def room_ranges(x: float, y: float, yaw: float, angles: np.ndarray, max_range: float) -> np.ndarray:
    """Distance to the walls of a square room |x|, |y| ≤ ROOM_HALF_M along each beam."""
    dx, dy = np.cos(yaw + angles), np.sin(yaw + angles)
    with np.errstate(divide="ignore", invalid="ignore"):
        tx = np.where(dx > 0, (ROOM_HALF_M - x) / dx, np.where(dx < 0, (-ROOM_HALF_M - x) / dx, np.inf))
        ty = np.where(dy > 0, (ROOM_HALF_M - y) / dy, np.where(dy < 0, (-ROOM_HALF_M - y) / dy, np.inf))
    r = np.minimum(tx, ty)
    return np.where(r <= max_range, r, np.inf)


def tf_msg(parent: str, child: str, stamp, xyz, quat) -> dict:
    return {
        "header": {"stamp": stamp, "frame_id": parent},
        "child_frame_id": child,
        "transform": {
            "translation": dict(zip("xyz", xyz, strict=True)),
            "rotation": dict(zip("xyzw", quat, strict=True)),
        },
    }


def main() -> None:
    sdf_path = Path(sys.argv[1]) if len(sys.argv) > 1 else REPO / "description" / "my_diff_car_control.sdf"
    text = sdf_path.read_text()
    model = sdf_loader.parse_model(text, check_files=False)
    node = Probe("fake_robot")
    state = {"x": 0.0, "y": 0.0, "yaw": 0.0, "v": 0.0, "w": 0.0, "cmd_t": 0.0, "wheel": 0.0}
    lock = threading.Lock()

    def on_cmd(msg) -> None:
        with lock:
            state["v"], state["w"] = float(msg.twist.linear.x), float(msg.twist.angular.z)
            state["cmd_t"] = time.monotonic()

    node.create_subscription("/diffbot_base_controller/cmd_vel", "geometry_msgs/msg/TwistStamped", on_cmd)
    desc = node.create_publisher("/robot_description", "std_msgs/msg/String", latched=True)
    tf_static = node.create_publisher("/tf_static", "tf2_msgs/msg/TFMessage", latched=True)
    tf = node.create_publisher("/tf", "tf2_msgs/msg/TFMessage")
    odom = node.create_publisher("/diffbot_base_controller/odom", "nav_msgs/msg/Odometry")
    joints = node.create_publisher("/joint_states", "sensor_msgs/msg/JointState")
    clock = node.create_publisher("/clock", "rosgraph_msgs/msg/Clock")
    scan = node.create_publisher("/scan", "sensor_msgs/msg/LaserScan")
    image = node.create_publisher("/camera/image_raw", "sensor_msgs/msg/Image")

    desc.publish({"data": text})
    start_ns = time.time_ns()
    stamp0 = {"sec": 0, "nanosec": 0}
    statics = []
    for j in model.joints:
        if j.type == "fixed":
            rel = model.link(j.parent).pose_model.inverse().compose(model.link(j.child).pose_model)
            statics.append(tf_msg(j.parent, j.child, stamp0, rel.xyz, rel.quat))
    root = model.link(model.root_link())
    statics.append(tf_msg("base_footprint", root.name, stamp0, root.pose_model.xyz, root.pose_model.quat))
    tf_static.publish({"transforms": statics})
    lidar = model.link("lidar_link").pose_model if any(lk.name == "lidar_link" for lk in model.links) else None
    angles = np.linspace(-math.pi, math.pi, 360, endpoint=False)
    print("ready", flush=True)

    period = 1.0 / RATE_HZ
    tick = 0
    next_t = time.monotonic()
    while True:
        next_t += period
        time.sleep(max(0.0, next_t - time.monotonic()))
        tick += 1
        with lock:
            if time.monotonic() - state["cmd_t"] > 0.5:  # diff_drive_controller's cmd_vel_timeout
                state["v"] = state["w"] = 0.0
            state["yaw"] += state["w"] * period
            state["x"] += state["v"] * math.cos(state["yaw"]) * period
            state["y"] += state["v"] * math.sin(state["yaw"]) * period
            state["wheel"] += state["v"] / 0.04 * period
            x, y, yaw, v, w = state["x"], state["y"], state["yaw"], state["v"], state["w"]
        ns = time.time_ns() - start_ns
        stamp = {"sec": ns // 1_000_000_000, "nanosec": ns % 1_000_000_000}
        q = (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))
        clock.publish({"clock": stamp})
        tf.publish({"transforms": [tf_msg("odom", "base_footprint", stamp, (x, y, 0.0), q)]})
        odom.publish(
            {
                "header": {"stamp": stamp, "frame_id": "odom"},
                "child_frame_id": "base_footprint",
                "pose": {"pose": {"position": {"x": x, "y": y}, "orientation": dict(zip("xyzw", q, strict=True))}},
                "twist": {"twist": {"linear": {"x": v}, "angular": {"z": w}}},
            }
        )
        if tick % 2 == 0:
            joints.publish(
                {
                    "header": {"stamp": stamp},
                    "name": ["base_link_to_left_wheel", "base_link_to_right_wheel"],
                    "position": [state["wheel"], state["wheel"]],
                    "velocity": [v / 0.04, v / 0.04],
                    "effort": [math.nan, math.nan],
                }
            )
        if tick % 5 == 0 and lidar is not None:
            lx = x + math.cos(yaw) * lidar.xyz[0] - math.sin(yaw) * lidar.xyz[1]
            ly = y + math.sin(yaw) * lidar.xyz[0] + math.cos(yaw) * lidar.xyz[1]
            ranges = room_ranges(lx, ly, yaw, angles, 10.0).astype(np.float32)
            scan.publish(
                types.new(
                    "sensor_msgs/msg/LaserScan",
                    {
                        "header": {"stamp": stamp, "frame_id": "lidar_link"},
                        "angle_min": -math.pi,
                        "angle_max": math.pi - 2 * math.pi / 360,
                        "angle_increment": 2 * math.pi / 360,
                        "range_min": 0.1,
                        "range_max": 10.0,
                        "ranges": ranges.tolist(),
                    },
                )
            )
        if tick % 10 == 0 and image.subscription_count > 0:
            w_px, h_px = 64, 48
            px = np.zeros((h_px, w_px, 3), np.uint8)
            px[:, :, 0] = np.linspace(0, 255, w_px, dtype=np.uint8)[None, :]
            px[:, :, 2] = (tick * 5) % 256
            image.publish(
                types.new(
                    "sensor_msgs/msg/Image",
                    {
                        "header": {"stamp": stamp, "frame_id": "camera_link"},
                        "height": h_px,
                        "width": w_px,
                        "encoding": "rgb8",
                        "step": w_px * 3,
                        "data": px.ravel(),
                    },
                )
            )


if __name__ == "__main__":
    try:
        main()
    except KeyboardInterrupt:
        pass
