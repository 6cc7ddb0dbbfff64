"""The scene (bus messages → JSON views), page commands, the security checks and PNG encoding, without I/O."""

from __future__ import annotations

import json
import math
import struct
import zlib
from pathlib import Path

import numpy as np
import pytest

from diffctl.errors import MessageError
from diffctl.interfaces import types
from diffctl.viz.commands import fill_now, parse_body, parse_publish, parse_teleop
from diffctl.viz.png import encode_png, image_data_url, image_pixels
from diffctl.viz.rates import RateMeter, RtfMeter
from diffctl.viz.rviz_config import default_config
from diffctl.viz.scene import Scene
from diffctl.viz.security import HostPolicy, query_token, token_matches
from diffctl.viz.server import to_json
from diffctl.viz.settings import VizSettings

REPO = Path(__file__).resolve().parents[2]
ODOM = "/diffbot_base_controller/odom"


def tfm(parent: str, child: str, x: float, y: float, yaw: float) -> dict:
    return {
        "header": {"frame_id": parent},
        "child_frame_id": child,
        "transform": {"translation": {"x": x, "y": y}, "rotation": {"z": math.sin(yaw / 2), "w": math.cos(yaw / 2)}},
    }


def odom_msg(x: float, y: float, yaw: float) -> object:
    return types.new(
        "nav_msgs/msg/Odometry",
        {
            "header": {"frame_id": "odom"},
            "child_frame_id": "base_footprint",
            "pose": {
                "pose": {"position": {"x": x, "y": y}, "orientation": {"z": math.sin(yaw / 2), "w": math.cos(yaw / 2)}}
            },
            "twist": {"twist": {"linear": {"x": 0.5}, "angular": {"z": 0.1}}},
        },
    )


def test_scene_views_in_the_fixed_frame() -> None:
    scene = Scene(default_config(), VizSettings())
    scene.set_robot_description((REPO / "description" / "my_diff_car_control.sdf").read_text())
    scene.on_tf(
        types.new("tf2_msgs/msg/TFMessage", {"transforms": [tfm("base_footprint", "lidar_link", 0, 0, 0)]}), static=True
    )
    scene.on_tf(
        types.new(
            "tf2_msgs/msg/TFMessage",
            {"transforms": [tfm("map", "odom", 10.0, 0.0, 0.0), tfm("odom", "base_footprint", 1.0, 0.0, math.pi / 2)]},
        )
    )
    for i in range(5):  # the trail keeps a pose every 5 cm
        scene.on_odometry(ODOM, odom_msg(0.03 * i, 0.0, 0.0))
    scan = types.new(
        "sensor_msgs/msg/LaserScan",
        {
            "header": {"frame_id": "lidar_link"},
            "angle_min": 0.0,
            "angle_increment": math.pi / 2,
            "range_min": 0.1,
            "range_max": 10.0,
            "ranges": [2.0, 3.0, math.inf, 0.05],
        },
    )
    scene.on_scan("/scan", scan)

    frame = scene.frame_view("map")
    assert frame["frames"]["base_footprint"][:2] == [11.0, 0.0] and frame["fixed_known"] is True
    assert scene.frame_view("earth")["fixed_known"] is False
    assert {p["link"] for p in frame["robot"]} >= {"base_link", "left_wheel", "right_wheel"}
    assert frame["odom"][0]["pose"] == [10.12, 0.0, 0.0]  # odometry is in odom, shown in map
    assert scene.paths_view("map")["paths"][ODOM] == [10.0, 0.0, 0.0, 10.06, 0.0, 0.0, 10.12, 0.0, 0.0]
    # Beams: 2 m ahead of a lidar turned 90° left (→ +y), 3 m to its left (→ −x); inf and < range_min dropped.
    assert scene.scan_view("map")["scans"]["/scan"]["pts"] == [11.0, 2.0, 8.0, 0.0]
    assert scene.scan_view("nowhere")["scans"]["/scan"]["ok"] is False
    # The robot moves on before the next scan: the points stay where they were seen.
    scene.on_tf(types.new("tf2_msgs/msg/TFMessage", {"transforms": [tfm("odom", "base_footprint", 2.0, 0.0, 0.0)]}))
    assert scene.scan_view("map")["scans"]["/scan"]["pts"] == [11.0, 2.0, 8.0, 0.0]
    assert scene.scan_view("base_footprint")["scans"]["/scan"]["pts"] == [-1.0, 2.0, -4.0, 0.0]
    assert scene.robot_view()["name"] == "my_diff_car"
    json.loads(to_json(frame))

    # Ground truth from the simulator (world frame): shown in root frames, not in a frame that moves.
    scene.on_ground_truth({"pose": [{"name": "robot", "position": {"x": 1.0, "y": 2.0}, "orientation": {"w": 1.0}}]})
    assert scene.frame_view("map")["gt"] == [1.0, 2.0, 0.0] and scene.frame_view("odom")["gt"] is None
    scene.on_tf(types.new("tf2_msgs/msg/TFMessage", {"transforms": [tfm("world", "map", -1.0, 0.0, 0.0)]}))
    assert scene.frame_view("odom")["gt"] == [-8.0, 2.0, 0.0]  # via TF: odom sits at x = 9 m in world
    scene.set_robot_description("<sdf version='1.8'><model name='m'><link name='a'><pose/></link></model></sdf>")
    assert scene.robot_view()["error"] and "pose" in scene.robot_view()["error"]
    # A jump back in sim time drops /tf and the trails (RViz's "Detected jump back in time").
    scene.on_clock(5.0, wall_s=100.0)
    scene.on_clock(1.0, wall_s=100.1)
    assert scene.time_jumps == 1 and scene.frame_view("map")["odom"][0]["pose"] is None
    assert scene.paths_view("odom")["paths"][ODOM] == []


def test_status_prefers_sim_stats_and_nan_becomes_null() -> None:
    scene = Scene(default_config(), VizSettings())
    js = types.new(
        "sensor_msgs/msg/JointState",
        {"name": ["l", "r"], "position": [1.0, 2.0], "velocity": [0.5], "effort": [math.nan, math.nan]},
    )
    scene.on_joint_states(js)
    status = scene.status_view()
    assert status["joints"] == [
        {"name": "l", "position": 1.0, "velocity": 0.5, "effort": None},
        {"name": "r", "position": 2.0, "velocity": None, "effort": None},
    ]
    assert status["rtf"] is None and status["sim_time"] is None
    scene.on_stats(
        {
            "sim_time": {"sec": 12, "nsec": 500_000_000},
            "real_time_factor": 0.98,
            "paused": False,
            "step_time_us": 11.5,
        }
    )
    status = scene.status_view()
    assert status["sim_time"] == 12.5 and status["rtf"] == 0.98 and status["rtf_source"] == "sim stats"
    assert status["sim"]["step_time_us"] == 11.5


def test_rate_and_rtf_meters() -> None:
    rates = RateMeter(window_s=2.0)
    for i in range(21):
        rates.record("/scan", 10.0 + i * 0.1)
    assert abs(rates.rate_hz("/scan", 12.0) - 10.0) < 1e-9
    assert rates.rate_hz("/scan", 20.0) is None and rates.rate_hz("/none", 0.0) is None
    rtf = RtfMeter()
    for i in range(11):
        rtf.record(i * 0.5, 100.0 + i * 0.1)  # 0.5 s of sim per 0.1 s of wall
    assert abs(rtf.rtf(101.0) - 5.0) < 1e-9 and rtf.rtf(200.0) is None


def test_teleop_and_publisher_commands_are_checked() -> None:
    s = VizSettings(max_linear_mps=1.0, max_angular_radps=2.0)
    cmd = parse_teleop({"linear": 5, "angular": -9.5}, s)
    assert (cmd.linear_mps, cmd.angular_radps, cmd.topic, cmd.stamped) == (1.0, -2.0, s.teleop_topic, True)
    assert cmd.fields({"sec": 1, "nanosec": 2}, "base_link")["twist"]["linear"]["x"] == 1.0
    assert parse_teleop({"topic": "cmd_vel", "stamped": False, "linear": 0.2}, s).fields({}, "") == {
        "linear": {"x": 0.2},
        "angular": {"z": 0.0},
    }
    for bad in ({"linear": math.inf}, {"angular": "fast"}, {"linear": True}, {"topic": "/a b"}, {"stamped": "yes"}):
        with pytest.raises(MessageError):
            parse_teleop(bad, s)
    job = parse_publish({"id": "j", "topic": "/chatter", "type": "std_msgs/String", "body": "data: hi", "rate": "5"}, s)
    assert (job.type_name, job.fields, job.rate_hz) == ("std_msgs/msg/String", {"data": "hi"}, 5.0)
    stamped = parse_publish({"topic": "/c", "type": "geometry_msgs/msg/TwistStamped", "body": "header: auto"}, s)
    assert fill_now(stamped.fields, {"sec": 5, "nanosec": 1}) == {
        "header": {"stamp": {"sec": 5, "nanosec": 1}, "frame_id": ""}
    }
    assert fill_now({"header": {"stamp": "now", "frame_id": "x"}}, {"sec": 1, "nanosec": 0})["header"]["stamp"] == {
        "sec": 1,
        "nanosec": 0,
    }
    assert parse_body('{"twist": {"linear": {"x": 0.5}}}') == {"twist": {"linear": {"x": 0.5}}}  # JSON works too
    cases = [
        ({"body": "data: [1, 2"}, "not valid YAML at line"),
        ({"body": "- 1"}, "must be a mapping"),
        ({"body": "datum: hi"}, "unknown field 'datum'"),
        ({"type": "std_msgs/msg/Nope"}, "unknown message type"),
        ({"rate": 1e6}, "between 0"),
        ({"topic": ""}, "topic"),
        ({"body": "x" * 70_000}, "at most"),
    ]
    for change, text in cases:
        with pytest.raises(MessageError) as e:
            parse_publish({"topic": "/chatter", "type": "std_msgs/msg/String", "body": "", **change}, s)
        assert text in str(e.value), (change, str(e.value))


def test_token_host_and_origin_checks() -> None:
    assert token_matches("abc", "abc") and not token_matches("abd", "abc") and not token_matches(None, "abc")
    assert query_token("/ws?token=x%2By&other=1") == "x+y" and query_token("/ws") is None
    p = HostPolicy("127.0.0.1", 8080)
    assert p.host_ok("127.0.0.1:8080") and p.host_ok("localhost:8080") and not p.host_ok("evil.example:8080")
    assert not p.host_ok("127.0.0.1:8081") and not p.host_ok(None)
    assert p.origin_ok("http://localhost:8080", "localhost:8080")
    assert not p.origin_ok("http://evil.example", "127.0.0.1:8080")
    assert not p.origin_ok("http://localhost:8080", "127.0.0.1:8080")  # same host:port only
    assert not p.origin_ok("null", "127.0.0.1:8080")
    assert p.origin_ok(None, "127.0.0.1:8080")  # a script, not a web page


def _decode_png(data: bytes) -> tuple[int, int, int, bytes]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos : pos + 4])
        tag, body = data[pos + 4 : pos + 8], data[pos + 8 : pos + 8 + n]
        assert struct.unpack(">I", data[pos + 8 + n : pos + 12 + n])[0] == zlib.crc32(tag + body)
        if tag == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif tag == b"IDAT":
            idat += body
        pos += 12 + n
    w, h, _, colour, *_ = ihdr
    return w, h, colour, zlib.decompress(idat)


def test_png_encoding_of_image_messages() -> None:
    px = np.arange(4 * 3 * 3, dtype=np.uint8).reshape(3, 4, 3)
    w, h, colour, raw = _decode_png(encode_png(px))
    assert (w, h, colour) == (4, 3, 2)
    rows = np.frombuffer(raw, np.uint8).reshape(3, 1 + 12)
    assert (rows[:, 0] == 0).all() and (rows[:, 1:].reshape(3, 4, 3) == px).all()
    bgr = image_pixels(4, 3, "bgr8", 12, px.tobytes())
    assert (bgr == px[:, :, ::-1]).all()
    depth = np.array([[1.0, 2.0], [math.nan, 3.0]], np.float32)
    grey = image_pixels(2, 2, "32FC1", 8, depth.tobytes())
    assert grey.tolist() == [[0, 127], [0, 255]]
    wide = image_pixels(1280, 2, "mono8", 1280, bytes(2560))
    assert wide.shape == (1, 640)  # decimated for the page
    with pytest.raises(MessageError):
        image_pixels(4, 3, "rgb8", 12, bytes(10))
    with pytest.raises(MessageError):
        image_pixels(4, 3, "yuv422", 8, bytes(24))
    msg = types.new(
        "sensor_msgs/msg/Image", {"width": 4, "height": 3, "encoding": "rgb8", "step": 12, "data": px.ravel()}
    )
    url, w, h = image_data_url(msg)
    assert url.startswith("data:image/png;base64,") and (w, h) == (4, 3)
