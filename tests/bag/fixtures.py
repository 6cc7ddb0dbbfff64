"""Bags made by other writers, in the tests: rosbags' rosbag2 Writer and the `mcap` library's Writer.

Nothing here is a checked-in binary; every fixture is produced by the library that real bags come from.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import yaml
from mcap.writer import CompressionType, Writer
from rosbags.rosbag2 import StoragePlugin
from rosbags.rosbag2 import Writer as RosbagsWriter
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

# test_msgs/msg/BasicTypes as ROS 2 Jazzy's test_interface_files define it (a type rosbags' store lacks).
BASIC_TYPES_MSG = """bool bool_value
byte byte_value
char char_value
float32 float32_value
float64 float64_value
int8 int8_value
uint8 uint8_value
int16 int16_value
uint16 uint16_value
int32 int32_value
uint32 uint32_value
int64 int64_value
uint64 uint64_value
"""
BASIC = "test_msgs/msg/BasicTypes"
SEC = 1_000_000_000
T0 = 1_700_000_000 * SEC


def rosbags_bag(path: Path, *, version: int = 8, zstd_chunks: bool = True, n: int = 20) -> dict[str, int]:
    """A rosbag2 MCAP bag by rosbags (metadata `version`), with Odometry, String and BasicTypes topics."""
    from rosbags.rosbag2.enums import CompressionFormat, CompressionMode

    ts = get_typestore(Stores.ROS2_JAZZY)
    ts.register(get_types_from_msg(BASIC_TYPES_MSG, BASIC))
    w = RosbagsWriter(path, version=version, storage_plugin=StoragePlugin.MCAP)
    if zstd_chunks:
        w.set_compression(CompressionMode.STORAGE, CompressionFormat.ZSTD)
    w.open()
    odom = w.add_connection("/odom", "nav_msgs/msg/Odometry", typestore=ts)
    chat = w.add_connection("/chatter", "std_msgs/msg/String", typestore=ts)
    basic = w.add_connection("/basic", BASIC, typestore=ts)
    for i in range(n):
        t = T0 + i * SEC // 10
        o = _odom(ts, i, t)
        w.write(odom, t, ts.serialize_cdr(o, "nav_msgs/msg/Odometry"))
        if i % 2 == 0:
            w.write(chat, t + 1, ts.serialize_cdr(ts.types["std_msgs/msg/String"](data=f"hello {i}"),
                                                  "std_msgs/msg/String"))
        if i % 4 == 0:
            w.write(basic, t + 2, ts.serialize_cdr(basic_msg(ts, i), BASIC))
    w.close()
    return {"/odom": n, "/chatter": (n + 1) // 2, "/basic": (n + 3) // 4}


def _odom(ts, i: int, t: int):
    T = ts.types
    pose = T["geometry_msgs/msg/PoseWithCovariance"](
        pose=T["geometry_msgs/msg/Pose"](position=T["geometry_msgs/msg/Point"](x=0.1 * i, y=0.0, z=0.0),
                                         orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0)),
        covariance=np.zeros(36))
    twist = T["geometry_msgs/msg/TwistWithCovariance"](
        twist=T["geometry_msgs/msg/Twist"](linear=T["geometry_msgs/msg/Vector3"](x=0.5, y=0.0, z=0.0),
                                           angular=T["geometry_msgs/msg/Vector3"](x=0.0, y=0.0, z=0.0)),
        covariance=np.zeros(36))
    hdr = T["std_msgs/msg/Header"](stamp=T["builtin_interfaces/msg/Time"](sec=t // SEC, nanosec=t % SEC),
                                   frame_id="odom")
    return T["nav_msgs/msg/Odometry"](header=hdr, child_frame_id="base_link", pose=pose, twist=twist)


def basic_msg(ts, i: int):
    return ts.types[BASIC](bool_value=True, byte_value=7, char_value=65, float32_value=1.5, float64_value=-2.25 * i,
                           int8_value=-8, uint8_value=8, int16_value=-16, uint16_value=16, int32_value=-32 * i,
                           uint32_value=32, int64_value=-(2**40), uint64_value=2**50)


def mcap_file(path: Path, compression: CompressionType, n: int = 30) -> int:
    """A bare ros2-profile MCAP (no metadata.yaml) with `compression` chunks, from the mcap library."""
    ts = get_typestore(Stores.ROS2_JAZZY)
    text, _ = ts.generate_msgdef("geometry_msgs/msg/Twist", ros_version=2)
    with open(path, "wb") as f:
        w = Writer(f, compression=compression, chunk_size=512)
        w.start(profile="ros2", library="test")
        sid = w.register_schema("geometry_msgs/msg/Twist", "ros2msg", text.encode())
        cid = w.register_channel("/cmd_vel", "cdr", sid, {"offered_qos_profiles": ""})
        T = ts.types
        for i in range(n):
            msg = T["geometry_msgs/msg/Twist"](linear=T["geometry_msgs/msg/Vector3"](x=float(i), y=0.0, z=0.0),
                                               angular=T["geometry_msgs/msg/Vector3"](x=0.0, y=0.0, z=0.5))
            w.add_message(cid, T0 + i * SEC // 20, bytes(ts.serialize_cdr(msg, "geometry_msgs/msg/Twist")),
                          T0 + i * SEC // 20)
        w.finish()
    return n


def downgrade(bag_dir: Path, version: int) -> None:
    """Rewrite a rosbags-made metadata.yaml as an older version wrote it: drop the keys later versions
    added, and from v8 down store offered_qos_profiles as a YAML string with integer enums."""
    path = bag_dir / "metadata.yaml"
    doc = yaml.safe_load(path.read_text())
    info = doc["rosbag2_bagfile_information"]
    info["version"] = version
    for key, since in (("ros_distro", 8), ("custom_data", 6), ("files", 5)):
        if version < since:
            info.pop(key, None)
    if version == 4:  # Foxy listed files with the bag folder in front
        info["relative_file_paths"] = [f"{bag_dir.name}/{p}" for p in info["relative_file_paths"]]
    for t in info["topics_with_message_count"]:
        tm = t["topic_metadata"]
        if version < 7:
            tm.pop("type_description_hash", None)
        tm["offered_qos_profiles"] = (
            "- history: 1\n  depth: 10\n  reliability: 1\n  durability: 2\n"
            "  deadline:\n    sec: 9223372036\n    nsec: 854775807\n"
            "  lifespan:\n    sec: 9223372036\n    nsec: 854775807\n  liveliness: 1\n"
            "  liveliness_lease_duration:\n    sec: 9223372036\n    nsec: 854775807\n"
            "  avoid_ros_namespace_conventions: false\n")
    path.write_text(yaml.safe_dump(doc))
