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
    if qw < 0.0:  # tf2_geometry_msgs answers with the representative whose w is not negative
        qx, qy, qz, qw = -qx, -qy, -qz, -qw
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


def _rotation_matrix(transform: Any) -> Any:
    import numpy as np

    _, q = _tq(transform)
    columns = [tm.rotate(q, axis) for axis in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))]
    return np.array(columns, dtype=np.float64).T


def transform_covariance(cov_in: Any, transform: Any) -> Any:
    """A 6x6 row-major pose covariance (36 values) seen from the transform's parent frame: each 3x3 block
    (position, orientation and their cross terms) is rotated as R·C·Rᵀ; the translation plays no part."""
    import numpy as np

    rotation = _rotation_matrix(transform)
    both = np.zeros((6, 6))
    both[:3, :3] = rotation
    both[3:, 3:] = rotation
    cov = np.asarray(cov_in, dtype=np.float64).reshape(6, 6)
    return (both @ cov @ both.T).reshape(36)


def do_transform_pose_with_covariance_stamped(pose: Any, transform: Any) -> Any:
    """PoseWithCovarianceStamped → PoseWithCovarianceStamped (the covariance rotated, see transform_covariance)."""
    from geometry_msgs.msg import PoseWithCovarianceStamped

    out = PoseWithCovarianceStamped()
    out.pose.pose = do_transform_pose(pose.pose.pose, transform)
    out.pose.covariance = transform_covariance(pose.pose.covariance, transform)
    _header(out, transform)
    return out


def do_transform_polygon_stamped(polygon: Any, transform: Any) -> Any:
    """PolygonStamped → PolygonStamped: every vertex moved (as float32 Point32s again)."""
    from geometry_msgs.msg import Point32, PolygonStamped

    t, q = _tq(transform)
    out = PolygonStamped()
    for vertex in polygon.polygon.points:
        x, y, z = tm.rotate(q, (vertex.x, vertex.y, vertex.z))
        out.polygon.points.append(Point32(x=x + t[0], y=y + t[1], z=z + t[2]))
    _header(out, transform)
    return out


def to_msg_msg(msg: Any) -> Any:
    """A stamped geometry message is already its own message form."""
    return msg


def from_msg_msg(msg: Any) -> Any:
    """… and its own Python form."""
    return msg


def register(registration: Any, conversions: Any) -> None:
    """Make Buffer.transform() take the stamped types and tf2_ros.convert() pass the stamped messages through
    unchanged (tf2_geometry_msgs does both on import)."""
    from geometry_msgs.msg import (
        PointStamped,
        PolygonStamped,
        PoseStamped,
        PoseWithCovarianceStamped,
        Vector3Stamped,
    )

    registration.add(PointStamped, do_transform_point)
    registration.add(Vector3Stamped, do_transform_vector3)
    registration.add(PoseStamped, do_transform_pose_stamped)
    registration.add(PoseWithCovarianceStamped, do_transform_pose_with_covariance_stamped)
    registration.add(PolygonStamped, do_transform_polygon_stamped)
    for kind in (Vector3Stamped, PoseStamped, PointStamped):
        conversions.add_to_msg(kind, to_msg_msg)
        conversions.add_from_msg(kind, from_msg_msg)
