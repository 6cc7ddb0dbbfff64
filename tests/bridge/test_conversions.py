"""Every type pair of the bridge, both ways, through the sim-side JSON encoding of diffctl.bus.gz."""

from __future__ import annotations

import base64
import math

import numpy as np
import pytest
from bridge_samples import GZ_SAMPLES

from diffctl.bridge import type_pairs
from diffctl.bridge.config import Direction
from diffctl.bus import gz, types
from diffctl.errors import MessageError


def test_every_pair_has_a_sample() -> None:
    assert {(p.ros_type, p.gz_type) for p in type_pairs.TYPE_PAIRS} == set(GZ_SAMPLES)


def _wire(gz_type: str, sample: dict) -> dict:
    # Through the sim-side encoding exactly as the simulator would put it on gz/… keys.
    _, fields = gz.decode(gz.encode(gz_type, sample), gz_type)
    return fields


@pytest.mark.parametrize(("ros_type", "gz_type"), sorted(GZ_SAMPLES))
def test_pair_round_trips_through_cdr_and_json(ros_type: str, gz_type: str) -> None:
    pair = type_pairs.lookup(ros_type, gz_type)
    assert pair is not None
    ros = pair.convert_to_ros(_wire(gz_type, GZ_SAMPLES[(ros_type, gz_type)]))
    # The ROS message is a real Jazzy message: it serializes and comes back equal.
    back_ros = types.deserialize(types.serialize(ros, ros_type), ros_type)
    back_gz = pair.convert_to_gz(back_ros)
    again = pair.convert_to_ros(_wire(gz_type, back_gz))
    assert types.to_dict(again) == types.to_dict(ros)


def _to_ros(ros_type: str, gz_type: str) -> object:
    pair = type_pairs.lookup(ros_type, gz_type)
    return pair.convert_to_ros(_wire(gz_type, GZ_SAMPLES[(ros_type, gz_type)]))


def test_clock_takes_sim_time() -> None:
    msg = _to_ros("rosgraph_msgs/msg/Clock", "gz.msgs.Clock")
    assert (msg.clock.sec, msg.clock.nanosec) == (3, 250)


def test_twist_stamped_keeps_header_and_frame() -> None:
    msg = _to_ros("geometry_msgs/msg/TwistStamped", "gz.msgs.Twist")
    assert msg.header.frame_id == "robot/base_link"
    assert (msg.header.stamp.sec, msg.header.stamp.nanosec) == (12, 500_000_000)
    assert (msg.twist.linear.x, msg.twist.angular.z) == (0.5, -0.25)


def test_odometry_frames_pose_and_twist() -> None:
    msg = _to_ros("nav_msgs/msg/Odometry", "gz.msgs.Odometry")
    assert (msg.header.frame_id, msg.child_frame_id) == ("odom", "base_link")
    assert (msg.pose.pose.position.x, msg.pose.pose.position.y) == (1.0, 2.0)
    assert (msg.pose.pose.orientation.z, msg.pose.pose.orientation.w) == (0.6, 0.8)
    assert (msg.twist.twist.linear.x, msg.twist.twist.angular.z) == (0.3, 0.1)
    gz_back = type_pairs.lookup("nav_msgs/msg/Odometry", "gz.msgs.Odometry").convert_to_gz(msg)
    assert gz.header_value(gz_back["header"], "child_frame_id") == "base_link"


def test_joint_state_from_model() -> None:
    msg = _to_ros("sensor_msgs/msg/JointState", "gz.msgs.Model")
    assert msg.name == ["left", "right"]
    assert msg.position.tolist() == [1.5, -1.0]
    assert msg.velocity.tolist() == [2.0, -2.0]
    assert msg.effort.tolist() == [0.1, 0.0]


def test_tf_from_pose_v_children_and_stamps() -> None:
    msg = _to_ros("tf2_msgs/msg/TFMessage", "gz.msgs.Pose_V")
    a, b = msg.transforms
    assert (a.header.frame_id, a.child_frame_id, a.transform.translation.x) == ("odom", "base_link", 1.0)
    # A pose without its own child_frame_id falls back to its scoped entity name; without a stamp, the vector's.
    assert (b.header.frame_id, b.child_frame_id, b.header.stamp.nanosec) == ("robot/base_link", "robot/lidar_link", 42)


def test_laser_scan_fields_and_middle_layer() -> None:
    msg = _to_ros("sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan")
    assert msg.header.frame_id == "robot/lidar_link"
    assert msg.angle_increment == pytest.approx(math.pi / 2)
    assert msg.ranges.dtype == np.float32 and math.isinf(msg.ranges[2])
    three_layers = dict(
        GZ_SAMPLES[("sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan")],
        vertical_count=3,
        ranges=[1.0] * 4 + [2.0] * 4 + [3.0] * 4,
        intensities=[],
    )
    pair = type_pairs.lookup("sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan")
    assert pair.convert_to_ros(three_layers).ranges.tolist() == [2.0] * 4


def test_imu_fields() -> None:
    msg = _to_ros("sensor_msgs/msg/Imu", "gz.msgs.IMU")
    assert (msg.header.frame_id, msg.angular_velocity.z, msg.linear_acceleration.z) == ("imu_link", 0.5, 9.81)
    assert msg.orientation.w == 1.0


def test_image_pixels_and_encodings() -> None:
    msg = _to_ros("sensor_msgs/msg/Image", "gz.msgs.Image")
    assert (msg.encoding, msg.width, msg.height, msg.step) == ("rgb8", 2, 2, 6)
    assert msg.data.tolist() == list(range(12))
    pair = type_pairs.lookup("sensor_msgs/msg/Image", "gz.msgs.Image")
    mono = {"width": 3, "height": 1, "pixel_format_type": "L_INT8", "data": base64.b64encode(b"abc").decode()}
    assert pair.convert_to_ros(mono).encoding == "mono8" and pair.convert_to_ros(mono).step == 3
    with pytest.raises(MessageError, match="expected step 3 x height 2"):
        pair.convert_to_ros(dict(mono, height=2))
    with pytest.raises(MessageError, match="pixel_format_type 'YUV'"):
        pair.convert_to_ros(dict(mono, pixel_format_type="YUV"))


def test_scalars() -> None:
    assert _to_ros("std_msgs/msg/String", "gz.msgs.StringMsg").data == "hello"
    assert _to_ros("std_msgs/msg/Int32", "gz.msgs.Int32").data == -7
    assert _to_ros("std_msgs/msg/Bool", "gz.msgs.Boolean").data is True


def test_ros_to_gz_twist_stamped_and_non_finite_commands_never_reach_the_sim() -> None:
    pair = type_pairs.lookup("geometry_msgs/msg/TwistStamped", "gz.msgs.Twist")
    msg = types.new(
        "geometry_msgs/msg/TwistStamped",
        {"header": {"frame_id": "base_link"}, "twist": {"linear": {"x": 0.7}, "angular": {"z": 1.2}}},
    )
    out = pair.convert_to_gz(msg)
    assert out["linear"]["x"] == 0.7 and out["angular"]["z"] == 1.2
    assert gz.header_value(out["header"], "frame_id") == "base_link"
    for bad in (math.nan, math.inf):
        msg = types.new("geometry_msgs/msg/Twist", {"linear": {"x": bad}})
        with pytest.raises(MessageError, match="non-finite"):
            type_pairs.lookup("geometry_msgs/msg/Twist", "gz.msgs.Twist").convert_to_gz(msg)
    with pytest.raises(MessageError, match="non-finite"):
        type_pairs.lookup("std_msgs/msg/Float64", "gz.msgs.Double").convert_to_gz(
            types.new("std_msgs/msg/Float64", {"data": math.nan})
        )


def test_malformed_gz_sample_is_a_message_error() -> None:
    pair = type_pairs.lookup("geometry_msgs/msg/Twist", "gz.msgs.Twist")
    with pytest.raises(MessageError, match=r"malformed gz\.msgs\.Twist"):
        pair.convert_to_ros({"linear": {"x": "fast"}})


def test_type_name_spellings() -> None:
    assert type_pairs.lookup("geometry_msgs/Twist", "ignition.msgs.Twist") is type_pairs.lookup(
        "geometry_msgs/msg/Twist", "gz.msgs.Twist"
    )
    assert type_pairs.lookup("geometry_msgs/msg/Twist", "gz.msgs.Odometry") is None
    assert Direction.GZ_TO_ROS.to_ros and not Direction.GZ_TO_ROS.to_gz
