"""navsat_transform_node on diffctl's client Node.

Subscribes to odometry/filtered, gps/fix and (until the transform is made, unless the heading comes from
odometry or a datum) imu; publishes odometry/gps (the fix as the robot's origin in the odometry's world
frame, to be fused by a state estimation node) and gps/filtered (the odometry back as a NavSatFix), and
with broadcast_cartesian_transform the world→utm (or local_enu) transform on /tf_static. Serves datum,
toLL, fromLL and setUTMZone. Checks every 1/frequency seconds of wall time, as upstream's wall timer.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from diffctl.interfaces import get_interface as msg
from diffctl.robot_localization import navsat_conversions as nc
from diffctl.robot_localization.navsat import NavSat, NavSatParams
from diffctl.robot_localization.ros_messages import TfTree, quat_of, stamp_ns, time_msg, transform_msg, xyz_of
from diffctl.robot_localization.rotations import Rigid, quat_from_rpy

STATUS_NO_FIX = -1
STATUS_GBAS_FIX = 2
COVARIANCE_TYPE_KNOWN = 3


class NavSatTransformNode:
    def __init__(self, node: Any) -> None:
        from diffctl.client.clock import Clock
        from diffctl.client.qos import QoSProfile, ReliabilityPolicy
        from diffctl.client.qos_overriding_options import QoSOverridingOptions

        self.node, self.log = node, node.get_logger()
        d = node.declare_parameter
        p = NavSatParams(
            magnetic_declination_rad=d("magnetic_declination_radians", 0.0).value,
            yaw_offset_rad=d("yaw_offset", 0.0).value,
            zero_altitude=d("zero_altitude", False).value,
        )
        self.publish_gps = d("publish_filtered_gps", True).value
        p.use_odometry_yaw = d("use_odometry_yaw", False).value
        p.use_manual_datum = d("wait_for_datum", False).value
        p.use_local_cartesian = d("use_local_cartesian", False).value
        frequency = d("frequency", 10.0).value
        delay = d("delay", 0.0).value
        d("transform_timeout", 0.0)
        if not frequency > 0.0:
            from diffctl.errors import ConfigError

            raise ConfigError(f"parameter 'frequency' must be greater than 0 Hz, got {frequency}")
        self.broadcast = d("broadcast_utm_transform", False).value
        if self.broadcast:
            self.log.warning("Parameter 'broadcast_utm_transform' has been deprecated. Please use "
                             "'broadcast_cartesian_transform' instead.")
        else:
            self.broadcast = d("broadcast_cartesian_transform", False).value
        self.as_parent = d("broadcast_utm_transform_as_parent_frame_", False).value
        if self.as_parent:
            self.log.warning("Parameter 'broadcast_utm_transform_as_parent_frame' has been deprecated. Please use "
                             "'broadcast_cartesian_transform_as_parent_frame' instead.")
        else:
            self.as_parent = d("broadcast_cartesian_transform_as_parent_frame", False).value

        self.tf = TfTree(node)
        self.core = NavSat(p, self.tf.lookup, self.log.error, self.log.info)
        node.create_service(msg("robot_localization/srv/SetDatum"), "datum", self.on_datum)
        node.create_service(msg("robot_localization/srv/ToLL"), "toLL", self.on_to_ll)
        node.create_service(msg("robot_localization/srv/FromLL"), "fromLL", self.on_from_ll)
        node.create_service(msg("robot_localization/srv/SetUTMZone"), "setUTMZone", self.on_set_utm_zone)
        if p.use_manual_datum:
            datum = list(d("datum", [0.0, 0.0, 0.0]).value)
            lat, lon, yaw = datum if len(datum) == 3 else (0.0, 0.0, 0.0)
            self.core.set_datum(lat, lon, 0.0, quat_from_rpy(0.0, 0.0, yaw))

        sensor = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
        overrides = QoSOverridingOptions.with_default_policies()
        node.create_subscription(msg("nav_msgs/msg/Odometry"), "odometry/filtered", self.on_odometry, sensor,
                                 qos_overriding_options=overrides)
        node.create_subscription(msg("sensor_msgs/msg/NavSatFix"), "gps/fix", self.on_fix, sensor,
                                 qos_overriding_options=overrides)
        self.imu_sub = None
        if not p.use_odometry_yaw and not p.use_manual_datum:
            self.imu_sub = node.create_subscription(msg("sensor_msgs/msg/Imu"), "imu", self.on_imu, sensor,
                                                    qos_overriding_options=overrides)
        self.gps_odom_pub = node.create_publisher(msg("nav_msgs/msg/Odometry"), "odometry/gps", QoSProfile(depth=10),
                                                  qos_overriding_options=overrides)
        self.filtered_pub = node.create_publisher(msg("sensor_msgs/msg/NavSatFix"), "gps/filtered",
                                                  QoSProfile(depth=10), qos_overriding_options=overrides) \
            if self.publish_gps else None
        self.static_pub = None
        if delay > 0:
            time.sleep(delay)
        node.create_timer(1.0 / frequency, self.on_timer, clock=Clock())

    def on_odometry(self, m: Any) -> None:
        pose = Rigid.from_xyz_quat(xyz_of(m.pose.pose.position), quat_of(m.pose.pose.orientation))
        self.core.on_odometry(m.header.frame_id, m.child_frame_id, pose, np.array(m.pose.covariance),
                              stamp_ns(m.header.stamp))

    def on_fix(self, m: Any) -> None:
        if not m.header.frame_id:
            self.log.error("NavSatFix message has empty frame_id. Will assume navsat device is mounted at robot's "
                           "origin")
        self.core.on_fix(m.header.frame_id, int(m.status.status) == STATUS_NO_FIX, m.latitude, m.longitude,
                         m.altitude, np.array(m.position_covariance), stamp_ns(m.header.stamp))

    def on_imu(self, m: Any) -> None:
        self.core.on_imu(m.header.frame_id, quat_of(m.orientation), stamp_ns(m.header.stamp))

    def on_timer(self) -> None:
        core = self.core
        if not core.transform_good:
            made = core.compute(self.node.get_clock().now_ns())
            if made is not None:
                if self.imu_sub is not None and not core.p.use_odometry_yaw and not core.p.use_manual_datum:
                    self.node.destroy_subscription(self.imu_sub)
                    self.imu_sub = None
                if self.broadcast:
                    self._broadcast(made)
            return
        gps = core.gps_odometry()
        if gps is not None:
            position, cov, stamp = gps
            m = msg("nav_msgs/msg/Odometry")()
            m.header.stamp = time_msg(stamp)
            m.header.frame_id = core.world_frame
            p = m.pose.pose.position
            p.x, p.y, p.z = (float(v) for v in position)
            m.pose.covariance = cov.ravel()
            self.gps_odom_pub.publish(m)
        if self.filtered_pub is not None:
            fix = core.filtered_fix()
            if fix is not None:
                (lat, lon, alt), cov, stamp = fix
                f = msg("sensor_msgs/msg/NavSatFix")()
                f.header.stamp = time_msg(stamp)
                f.header.frame_id = core.base_link_frame
                f.latitude, f.longitude, f.altitude = lat, lon, alt
                f.position_covariance = cov.ravel()
                f.position_covariance_type = COVARIANCE_TYPE_KNOWN
                f.status.status = STATUS_GBAS_FIX
                self.filtered_pub.publish(f)

    def _broadcast(self, cartesian_world: Rigid) -> None:
        from diffctl.client.qos import DurabilityPolicy, QoSProfile

        core = self.core
        frame = "local_enu" if core.local is not None else "utm"
        t = cartesian_world.inverse() if self.as_parent else cartesian_world
        t = Rigid(t.rot, np.array([t.trans[0], t.trans[1], 0.0 if core.p.zero_altitude else t.trans[2]]))
        parent, child = (frame, core.world_frame) if self.as_parent else (core.world_frame, frame)
        if self.static_pub is None:
            self.static_pub = self.node.create_publisher(
                msg("tf2_msgs/msg/TFMessage"), "/tf_static",
                QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL))
        tf = msg("tf2_msgs/msg/TFMessage")()
        tf.transforms = [transform_msg(self.node.get_clock().now_ns(), parent, child, t)]
        self.static_pub.publish(tf)

    # --- services -----------------------------------------------------------------------------------------------
    def on_datum(self, request: Any, response: Any) -> Any:
        g = request.geo_pose
        self.core.set_datum(g.position.latitude, g.position.longitude, g.position.altitude, quat_of(g.orientation))
        return response

    def on_to_ll(self, request: Any, response: Any) -> Any:
        if self.core.transform_good:
            lat, lon, alt = self.core.world_to_geodetic(np.array(xyz_of(request.map_point)))
            response.ll_point.latitude, response.ll_point.longitude, response.ll_point.altitude = lat, lon, alt
        return response

    def on_from_ll(self, request: Any, response: Any) -> Any:
        if self.core.transform_good:
            ll = request.ll_point
            p = self.core.geodetic_to_world(ll.latitude, ll.longitude, ll.altitude)
            response.map_point.x, response.map_point.y, response.map_point.z = (float(v) for v in p)
        return response

    def on_set_utm_zone(self, request: Any, response: Any) -> Any:
        try:
            zone, north = nc.parse_zone(request.utm_zone)
        except ValueError as e:
            self.log.error(str(e))
            return response
        self.core.set_utm_zone(zone, north)
        return response


def run() -> int:
    """Start navsat_transform_node with this process's ROS arguments; spin until shut down."""
    from diffctl.client import component
    from diffctl.client.node import Node

    def make() -> Node:
        node = Node("navsat_transform_node")
        NavSatTransformNode(node)
        return node

    return component.run(make)
