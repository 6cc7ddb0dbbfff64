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
