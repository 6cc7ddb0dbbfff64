"""The rmw_zenoh (Jazzy) wire format, checked byte for byte against design.md's layout."""

from __future__ import annotations

import struct

import numpy as np
import pytest

from diffctl.bus import wire
from diffctl.errors import MessageError
from diffctl.interfaces import types

TWIST_STAMPED_HASH = "RIHS01_5f0fcd4f81d5d06ad9b4c4c63e3ea51b82d6ae4d0558f1d475229b1121db6f64"


def test_twist_stamped_key_expression() -> None:
    key = wire.topic_key(0, "/diffbot_base_controller/cmd_vel", "geometry_msgs/msg/TwistStamped")
    assert key == f"0/diffbot_base_controller/cmd_vel/geometry_msgs::msg::dds_::TwistStamped_/{TWIST_STAMPED_HASH}"
    assert wire.topic_key(3, "chatter", "std_msgs/msg/String").startswith("3/chatter/std_msgs::msg::dds_::String_/")


def test_attachment_layout_is_33_bytes_seq_ts_len_gid() -> None:
    gid = bytes(range(16))
    att = wire.pack_attachment(7, 1_700_000_000_123_456_789, gid)
    assert len(att) == 33
    assert struct.unpack_from("<q", att, 0)[0] == 7
    assert struct.unpack_from("<q", att, 8)[0] == 1_700_000_000_123_456_789
    assert att[16] == 0x10 and att[17:] == gid
    assert wire.unpack_attachment(att) == (7, 1_700_000_000_123_456_789, gid)
    with pytest.raises(MessageError):
        wire.unpack_attachment(att[:-1])


def test_attachment_matches_zenoh_ext_serializer() -> None:
    from zenoh import ext

    gid = bytes(range(16, 32))
    ours = wire.pack_attachment(42, 123456789, gid)
    theirs = ext.z_serialize((ext.Int64(42), ext.Int64(123456789), gid)).to_bytes()
    assert ours == theirs


def test_cdr_payload_has_little_endian_encapsulation_header() -> None:
    msg = types.new("geometry_msgs/msg/TwistStamped", {"twist": {"linear": {"x": 0.5}}})
    raw = types.serialize(msg, "geometry_msgs/msg/TwistStamped")
    assert raw[:4] == b"\x00\x01\x00\x00"
    # 4 header + 8 stamp + 4 length + 1 NUL (empty frame_id), padded to 8, + 6 float64 = 68 bytes, as Fast-CDR.
    assert len(raw) == 68
    assert struct.unpack_from("<d", raw, 4 + 16)[0] == 0.5


def test_liveliness_tokens_follow_rmw_zenoh() -> None:
    tok = wire.entity_token(
        0,
        "abc123",
        0,
        10,
        wire.KIND_PUB,
        "/",
        "teleop",
        "/cmd_vel",
        "geometry_msgs/msg/TwistStamped",
        wire.qos_string(reliable=False, depth=1),
    )
    assert tok == (
        f"@ros2_lv/0/abc123/0/10/MP/%/%/teleop/%cmd_vel/geometry_msgs::msg::dds_::TwistStamped_/"
        f"{TWIST_STAMPED_HASH}/2::,1:,:,:,,"
    )
    ent = wire.parse_token(tok)
    assert ent is not None
    assert (ent.kind, ent.node_fqn, ent.topic, ent.type) == (
        "MP",
        "/teleop",
        "/cmd_vel",
        "geometry_msgs/msg/TwistStamped",
    )
    node = wire.parse_token(wire.node_token(0, "abc", 1, "/robot1", "sim"))
    assert node is not None and node.node_fqn == "/robot1/sim"


def test_service_hash_matches_rmw_zenoh_design_example() -> None:
    # design.md: 2/add_two_ints/example_interfaces::srv::dds_::AddTwoInts_/RIHS01_e118de6b…239c81a;
    # the same construction gives our service hashes.
    from diffctl.interfaces.typedefs import srv_typesdict
    from diffctl.interfaces.types import _ensure

    ts = _ensure("service_msgs/msg/ServiceEventInfo")  # with client_gid as rosidl types it (uint8[16])
    if "example_interfaces/srv/AddTwoInts" not in ts.types:
        ts.register(srv_typesdict("example_interfaces/srv/AddTwoInts", "int64 a\nint64 b", "int64 sum"))
    h = ts.hash_rihs01("example_interfaces/srv/AddTwoInts")
    assert h.startswith("RIHS01_e118de6b") and h.endswith("239c81a")


PROJECT_TYPES = [
    "geometry_msgs/msg/Twist",
    "geometry_msgs/msg/TwistStamped",
    "nav_msgs/msg/Odometry",
    "sensor_msgs/msg/JointState",
    "sensor_msgs/msg/LaserScan",
    "sensor_msgs/msg/Imu",
    "sensor_msgs/msg/Image",
    "tf2_msgs/msg/TFMessage",
    "rosgraph_msgs/msg/Clock",
    "std_msgs/msg/String",
    "std_msgs/msg/Float64MultiArray",
    "control_msgs/msg/DynamicJointState",
    "controller_manager_msgs/msg/ControllerState",
    "controller_manager_msgs/msg/HardwareComponentState",
]


@pytest.mark.parametrize("typename", PROJECT_TYPES)
def test_every_project_type_round_trips(typename: str) -> None:
    msg = types.new(typename, {})
    back = types.deserialize(types.serialize(msg, typename), typename)
    assert types.to_dict(back) == types.to_dict(msg)
    assert types.type_hash(typename).startswith("RIHS01_")


def test_values_round_trip_with_arrays() -> None:
    odom = types.new(
        "nav_msgs/msg/Odometry",
        {
            "header": {"frame_id": "odom", "stamp": {"sec": 3, "nanosec": 5}},
            "child_frame_id": "base_footprint",
            "pose": {"pose": {"position": {"x": 1.5}}, "covariance": [0.1] * 36},
        },
    )
    back = types.deserialize(types.serialize(odom, "nav_msgs/msg/Odometry"), "nav_msgs/msg/Odometry")
    assert back.pose.pose.position.x == 1.5 and back.child_frame_id == "base_footprint"
    assert np.allclose(back.pose.covariance, 0.1)


@pytest.mark.parametrize(
    "values, needle",
    [
        ({"twist": {"linaer": {"x": 1}}}, "did you mean 'linear'"),
        ({"twist": {"linear": {"x": "fast"}}}, "twist.linear.x"),
        ({"header": {"stamp": {"sec": 2**40}}}, "out of range"),
        ({"twist": 5}, "must be a mapping"),
    ],
)
def test_bad_values_name_the_field(values: dict, needle: str) -> None:
    with pytest.raises(MessageError, match=needle.replace("(", r"\(").replace("'", "'")):
        types.new("geometry_msgs/msg/TwistStamped", values)


def test_unknown_type_suggests_close_matches() -> None:
    with pytest.raises(MessageError, match="TwistStamped"):
        types.check("geometry_msgs/msg/TwistStampd")


def test_truncated_payload_is_a_message_error() -> None:
    raw = types.serialize(types.new("nav_msgs/msg/Odometry", {}), "nav_msgs/msg/Odometry")
    with pytest.raises(MessageError):
        types.deserialize(raw[:40], "nav_msgs/msg/Odometry")
