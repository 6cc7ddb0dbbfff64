"""tf2_py's message-level BufferCore and tf2_geometry_msgs through the overlay's ROS names (no node): the
same transforms as ROS gives, checked against Bullet's LinearMath."""

from __future__ import annotations

import math

import pybullet
import pytest
import tf2_geometry_msgs
import tf2_py
from builtin_interfaces.msg import Time
from geometry_msgs.msg import PointStamped, Pose, TransformStamped, Vector3Stamped


def stamped(parent: str, child: str, sec: int, xyz, q) -> TransformStamped:
    t = TransformStamped()
    t.header.frame_id, t.child_frame_id = parent, child
    t.header.stamp = Time(sec=sec, nanosec=0)
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = xyz
    r = t.transform.rotation
    r.x, r.y, r.z, r.w = q
    return t


def test_message_level_core_and_do_transform() -> None:
    core = tf2_py.BufferCore()
    q1 = pybullet.getQuaternionFromEuler([0.0, 0.0, math.pi / 2])
    q2 = pybullet.getQuaternionFromEuler([0.2, 0.0, 0.0])
    core.set_transform_static(stamped("map", "odom", 0, (1.0, 0.0, 0.0), q1), "test")
    core.set_transform(stamped("odom", "base", 3, (0.0, 2.0, 0.5), q2), "test")
    t = core.lookup_transform_core("map", "base", Time(sec=0, nanosec=0))
    assert (t.header.frame_id, t.child_frame_id, t.header.stamp.sec) == ("map", "base", 3)
    expected = pybullet.multiplyTransforms([1.0, 0.0, 0.0], q1, [0.0, 2.0, 0.5], q2)
    tr = t.transform.translation
    assert [tr.x, tr.y, tr.z] == pytest.approx(list(expected[0]))
    assert core.can_transform_core("map", "nowhere", Time()) == (
        False, 'Invalid frame ID "nowhere" passed to canTransform argument source_frame - frame does not exist')
    with pytest.raises(tf2_py.ExtrapolationException):
        core.lookup_transform_core("map", "base", Time(sec=4))

    p = PointStamped()
    p.header.frame_id = "base"
    p.point.x, p.point.y, p.point.z = 1.0, 2.0, 3.0
    out = tf2_geometry_msgs.do_transform_point(p, t)
    want = pybullet.multiplyTransforms(*expected, [1.0, 2.0, 3.0], [0, 0, 0, 1])[0]
    assert (out.header.frame_id, [out.point.x, out.point.y, out.point.z]) == ("map", pytest.approx(list(want)))
    v = Vector3Stamped()
    v.vector.x = 1.0
    rotated = tf2_geometry_msgs.do_transform_vector3(v, t).vector
    want_v = pybullet.multiplyTransforms([0, 0, 0], expected[1], [1.0, 0.0, 0.0], [0, 0, 0, 1])[0]
    assert [rotated.x, rotated.y, rotated.z] == pytest.approx(list(want_v))
    pose = Pose()
    pose.position.z = 1.0
    pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w = q2
    moved = tf2_geometry_msgs.do_transform_pose(pose, t)
    want_p = pybullet.multiplyTransforms(*expected, [0.0, 0.0, 1.0], q2)
    o = moved.orientation
    assert [moved.position.x, moved.position.y, moved.position.z] == pytest.approx(list(want_p[0]))
    assert [o.x, o.y, o.z, o.w] == pytest.approx(list(want_p[1])) or \
        [o.x, o.y, o.z, o.w] == pytest.approx([-c for c in want_p[1]])


def test_covariance_polygon_and_conversions() -> None:
    """PoseWithCovarianceStamped's 6x6 covariance turns with the transform's rotation (both the position and the
    orientation blocks, Bullet's matrix of the quaternion), PolygonStamped's vertices move as points do, a pose's
    quaternion comes back with w >= 0, and tf2_ros.convert passes the stamped messages through."""
    import numpy as np
    import tf2_ros
    from geometry_msgs.msg import Point32, PolygonStamped, PoseWithCovarianceStamped

    q = pybullet.getQuaternionFromEuler([0.3, -0.4, 1.1])
    t = stamped("map", "base", 2, (1.0, -2.0, 0.5), q)
    rotation = np.array(pybullet.getMatrixFromQuaternion(q)).reshape(3, 3)
    cov = np.arange(36, dtype=np.float64).reshape(6, 6)
    pose = PoseWithCovarianceStamped()
    pose.header.frame_id = "base"
    pose.pose.covariance = cov.reshape(36)
    pose.pose.pose.orientation.w = 1.0
    out = tf2_geometry_msgs.do_transform_pose_with_covariance_stamped(pose, t)
    got = np.asarray(out.pose.covariance).reshape(6, 6)
    for rows in (slice(0, 3), slice(3, 6)):
        for cols in (slice(0, 3), slice(3, 6)):
            assert got[rows, cols] == pytest.approx(rotation @ cov[rows, cols] @ rotation.T)
    assert list(tf2_geometry_msgs.transform_covariance(cov.reshape(36), t)) == pytest.approx(list(got.reshape(36)))
    assert (out.header.frame_id, out.header.stamp.sec) == ("map", 2)
    o = out.pose.pose.orientation
    assert [o.x, o.y, o.z, o.w] == pytest.approx(list(q))

    polygon = PolygonStamped()
    polygon.polygon.points = [Point32(x=1.0, y=2.0, z=3.0), Point32(x=-1.0, y=0.5, z=0.0)]
    moved = tf2_geometry_msgs.do_transform_polygon_stamped(polygon, t)
    assert moved.header.frame_id == "map"
    for before, after in zip(polygon.polygon.points, moved.polygon.points, strict=True):
        want = pybullet.multiplyTransforms([1.0, -2.0, 0.5], q, [before.x, before.y, before.z], [0, 0, 0, 1])[0]
        assert [after.x, after.y, after.z] == pytest.approx(list(want), abs=1e-6)

    half_turn = stamped("a", "b", 0, (0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0))
    flipped = Pose()
    flipped.orientation.x, flipped.orientation.w = 1.0, 0.0
    o = tf2_geometry_msgs.do_transform_pose(flipped, half_turn).orientation
    assert [o.x, o.y, o.z, o.w] == pytest.approx([0.0, 0.0, 0.0, 1.0])

    point = PointStamped()
    point.point.x = 4.0
    assert tf2_ros.convert(point, PointStamped) == point


def test_module_attributes_as_ros_loads_them() -> None:
    """ROS's tf2_py extension imports rclpy.time, and tf2_ros imports its submodules and rclpy.action, so code
    written against them reaches these names after plain imports (a fresh interpreter: nothing loaded before)."""
    import subprocess
    import sys

    program = (
        "import rclpy, tf2_py\n"
        "assert rclpy.time.Time is not None\n"
        "import tf2_ros\n"
        "assert rclpy.action.ActionClient is not None\n"
        "assert tf2_ros.BufferClient is tf2_ros.buffer_client.BufferClient\n"
        "assert tf2_ros.buffer.Buffer is tf2_ros.Buffer\n"
        "assert tf2_ros.transform_listener.TransformListener is tf2_ros.TransformListener\n"
    )
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
