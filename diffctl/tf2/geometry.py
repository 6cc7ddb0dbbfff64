"""tf2_geometry_msgs' do_transform_* functions: geometry_msgs values moved by a TransformStamped."""

from __future__ import annotations

from typing import Any

from diffctl.tf2 import transform_math as tm


def _tq(transform: Any) -> tuple[tm.Vec, tm.Quat]:
    t, q = transform.transform.translation, transform.transform.rotation
    return (t.x, t.y, t.z), (q.x, q.y, q.z, q.w)


def _header(msg: Any, transform: Any) -> None:
    # The result is stamped as the transform is: in its frame, at its time.
    msg.header.frame_id = transform.header.frame_id
    msg.header.stamp = transform.header.stamp


def do_transform_point(point: Any, transform: Any) -> Any:
    """PointStamped → PointStamped."""
    from geometry_msgs.msg import PointStamped

    t, q = _tq(transform)
    p = tm.rotate(q, (point.point.x, point.point.y, point.point.z))
    out = PointStamped()
    out.point.x, out.point.y, out.point.z = p[0] + t[0], p[1] + t[1], p[2] + t[2]
    _header(out, transform)
    return out


def do_transform_vector3(vector3: Any, transform: Any) -> Any:
    """Vector3Stamped → Vector3Stamped (rotation only)."""
    from geometry_msgs.msg import Vector3Stamped

    _, q = _tq(transform)
    v = tm.rotate(q, (vector3.vector.x, vector3.vector.y, vector3.vector.z))
    out = Vector3Stamped()
    out.vector.x, out.vector.y, out.vector.z = v
    _header(out, transform)
    return out


def do_transform_pose(pose: Any, transform: Any) -> Any:
    """Pose → Pose."""
    from geometry_msgs.msg import Pose

    t, q = _tq(transform)
    o = pose.orientation
    (px, py, pz), (qx, qy, qz, qw) = tm.compose(t, q, (pose.position.x, pose.position.y, pose.position.z),
                                                (o.x, o.y, o.z, o.w))
    out = Pose()
    out.position.x, out.position.y, out.position.z = px, py, pz
    out.orientation.x, out.orientation.y, out.orientation.z, out.orientation.w = qx, qy, qz, qw
    return out


def do_transform_pose_stamped(pose: Any, transform: Any) -> Any:
    """PoseStamped → PoseStamped."""
    from geometry_msgs.msg import PoseStamped

    out = PoseStamped()
    out.pose = do_transform_pose(pose.pose, transform)
    _header(out, transform)
    return out


def register(registration: Any) -> None:
    """Make Buffer.transform() take the stamped types (tf2_geometry_msgs does this on import)."""
    from geometry_msgs.msg import PointStamped, PoseStamped, Vector3Stamped

    registration.add(PointStamped, do_transform_point)
    registration.add(Vector3Stamped, do_transform_vector3)
    registration.add(PoseStamped, do_transform_pose_stamped)
