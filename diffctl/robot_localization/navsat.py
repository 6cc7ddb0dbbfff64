"""navsat_transform_node's geometry: the transform from the GPS's Cartesian frame (UTM grid or local ENU) to
the robot's world frame, fixed once the first odometry, GPS fix and heading are in, and the conversions
through it both ways.

The world pose of the first odometry with only its yaw kept, against the Cartesian pose of the robot's
origin at the first fix oriented by the IMU's yaw (plus magnetic declination, yaw_offset and, on UTM, the
meridian convergence): world ← cartesian = world_pose · cartesian_pose⁻¹. GPS antennas off the body origin
are corrected through the base_link ← gps transform. Pure: frames come from the node's `lookup`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from diffctl.robot_localization import navsat_conversions as nc
from diffctl.robot_localization.rotations import Rigid, from_quat, from_rpy, rot_z, to_rpy
from diffctl.robot_localization.state import wrap_angle

Lookup = Callable[[str, str, int], Rigid | None]
Log = Callable[[str], None]


@dataclass
class NavSatParams:
    magnetic_declination_rad: float = 0.0
    yaw_offset_rad: float = 0.0
    zero_altitude: bool = False
    use_odometry_yaw: bool = False
    use_manual_datum: bool = False
    use_local_cartesian: bool = False


def _rot6(rot: np.ndarray) -> np.ndarray:
    r = np.zeros((6, 6))
    r[:3, :3] = rot
    r[3:, 3:] = rot
    return r


def _translation(xyz: tuple[float, float, float] | np.ndarray) -> Rigid:
    return Rigid(np.eye(3), np.array(xyz, dtype=float))


class NavSat:
    def __init__(self, p: NavSatParams, lookup: Lookup, error: Log, info: Log) -> None:
        self.p, self.lookup, self.error, self.info = p, lookup, error, info
        self.world_frame, self.base_link_frame, self.gps_frame = "odom", "base_link", ""
        self.transform_good = False
        self.has_odom = self.has_gps = self.has_imu = False
        self.gps_updated = self.odom_updated = False
        self.force_user_utm = False
        self.utm_zone, self.north = 0, True
        self.convergence_rad = 0.0
        self.local = nc.LocalCartesian() if p.use_local_cartesian else None
        self.world_pose = Rigid.identity()  # the odometry when the transform was computed
        self.cartesian_pose = Rigid.identity()  # the fix (robot origin, once corrected) then
        self.orientation = np.eye(3)  # the heading source's orientation then (mounting removed)
        self.cartesian_world = Rigid.identity()
        self.world_cartesian = Rigid.identity()
        self.latest_cartesian = Rigid.identity()
        self.latest_cartesian_cov = np.zeros((6, 6))
        self.latest_world = Rigid.identity()
        self.latest_odom_cov = np.zeros((6, 6))
        self.gps_stamp_ns = self.odom_stamp_ns = 0
        self.manual_datum: tuple[float, float, float, tuple[float, float, float, float]] | None = None

    # --- inputs -------------------------------------------------------------------------------------------------
    def on_odometry(self, frame_id: str, child_frame_id: str, pose: Rigid, covariance: np.ndarray,
                    stamp_ns: int) -> None:
        self.world_frame, self.base_link_frame = frame_id, child_frame_id
        if not self.transform_good:
            self._set_odometry(pose, child_frame_id, stamp_ns)
        self.latest_world = pose
        self.latest_odom_cov = np.array(covariance, dtype=float).reshape(6, 6)
        self.odom_stamp_ns = stamp_ns
        self.odom_updated = True

    def _set_odometry(self, pose: Rigid, child_frame_id: str, stamp_ns: int) -> None:
        self.world_pose = pose
        self.has_odom = True
        if not self.transform_good and self.p.use_odometry_yaw and not self.p.use_manual_datum:
            self.on_imu(child_frame_id, pose.quat(), stamp_ns)

    def on_imu(self, frame_id: str, q: tuple[float, float, float, float], stamp_ns: int) -> None:
        """The heading source (needs the odometry first, for base_link's name)."""
        if not self.has_odom:
            return
        mount = self.lookup(self.base_link_frame, frame_id, stamp_ns)
        if mount is None and frame_id == self.base_link_frame:
            mount = Rigid.identity()
        if mount is None:
            return
        m_rpy, rpy = to_rpy(mount.rot), to_rpy(from_quat(*q))
        corrected = rot_z(m_rpy[2]) @ np.array([wrap_angle(rpy[i] - m_rpy[i]) for i in range(3)])
        self.orientation = from_rpy(*corrected)
        self.has_imu = True

    def on_fix(self, frame_id: str, no_fix: bool, lat: float, lon: float, alt: float, covariance: np.ndarray,
               stamp_ns: int) -> None:
        self.gps_frame = frame_id
        if no_fix or math.isnan(alt) or math.isnan(lat) or math.isnan(lon):
            return
        if not self.transform_good and not self.p.use_manual_datum:
            self._set_gps(lat, lon, alt)
        x, y = self._to_cartesian(lat, lon, alt)
        self.latest_cartesian = _translation((x, y, alt))
        self.latest_cartesian_cov = np.zeros((6, 6))
        self.latest_cartesian_cov[:3, :3] = np.array(covariance, dtype=float).reshape(3, 3)
        self.gps_stamp_ns = stamp_ns
        self.gps_updated = True

    def _to_cartesian(self, lat: float, lon: float, alt: float) -> tuple[float, float]:
        if self.local is not None:
            e, n, _ = self.local.forward(lat, lon, alt)
            return e, n
        # In the zone the transform was made in, so a drive across a zone border does not jump.
        x, y, *_ = nc.to_grid(lat, lon, self.utm_zone if self.has_gps else None)
        return x, y

    def _set_gps(self, lat: float, lon: float, alt: float) -> None:
        if self.local is not None:
            self.local.reset(lat, lon, 0.0)
            x, y, _ = self.local.forward(lat, lon, alt)
            self.convergence_rad = 0.0
        else:
            try:
                x, y, zone, north, gamma = nc.to_grid(lat, lon, self.utm_zone if self.force_user_utm else None)
            except Exception as e:  # PROJ refuses a point outside its zone's domain
                self.error(str(e))
                return
            self.utm_zone, self.north = zone, north
            self.convergence_rad = math.radians(gamma)
        self.info(f"Datum (latitude, longitude, altitude) is ({lat:0.2f}, {lon:0.2f}, {alt:0.2f})")
        self.info(f"Datum {'Local Cartesian' if self.local is not None else 'UTM'} coordinate is "
                  f"({self.utm_zone} {'north' if self.north else 'south'}, {x:0.2f}, {y:0.2f})")
        self.cartesian_pose = _translation((x, y, alt))
        self.has_gps = True

    # --- services -----------------------------------------------------------------------------------------------
    def set_datum(self, lat: float, lon: float, alt: float, q: tuple[float, float, float, float]) -> None:
        """Use this datum from now on (computed at the next cycle, once odometry names the frames)."""
        self.manual_datum = (lat, lon, alt, q)
        self.p.use_manual_datum = True
        self.transform_good = False

    def set_utm_zone(self, zone: int, north: bool) -> None:
        self.utm_zone, self.north = zone, north
        self.force_user_utm = True
        self.p.use_manual_datum = False
        self.transform_good = False
        self.has_gps = False
        self.info(f"UTM zone set to {zone} {'north' if north else 'south'}")

    def _apply_manual_datum(self, now_ns: int) -> None:
        if self.manual_datum is None:
            return
        lat, lon, alt, q = self.manual_datum
        self._set_gps(lat, lon, alt)
        self._set_odometry(Rigid.identity(), self.base_link_frame, now_ns)
        self.on_imu(self.base_link_frame, q, now_ns)

    # --- the transform ------------------------------------------------------------------------------------------
    def heading_offset(self) -> float:
        return self.p.magnetic_declination_rad + self.p.yaw_offset_rad + self.convergence_rad

    def compute(self, now_ns: int) -> Rigid | None:
        """Fix the cartesian → world transform when everything is in; returns it when it was just made."""
        if not self.transform_good and self.has_odom and self.p.use_manual_datum:
            self._apply_manual_datum(now_ns)
        if self.transform_good or not (self.has_odom and self.has_gps and self.has_imu):
            return None
        origin = self.cartesian_pose if self.p.use_manual_datum else self._robot_origin_cartesian(self.cartesian_pose)
        imu_yaw = to_rpy(self.orientation)[2] + self.heading_offset()
        self.info(f"Corrected for magnetic declination of {self.p.magnetic_declination_rad}, user-specified "
                  f"offset of {self.p.yaw_offset_rad} and meridian convergence of {self.convergence_rad}. "
                  f"Transform heading factor is now {imu_yaw}")
        cartesian = Rigid(rot_z(imu_yaw), origin.trans)
        world_yaw_only = Rigid(rot_z(to_rpy(self.world_pose.rot)[2]), self.world_pose.trans)
        self.cartesian_world = world_yaw_only * cartesian.inverse()
        self.world_cartesian = self.cartesian_world.inverse()
        self.transform_good = True
        return self.cartesian_world

    def _robot_origin_cartesian(self, gps_pose: Rigid) -> Rigid:
        offset = self.lookup(self.base_link_frame, self.gps_frame, 0)
        if offset is None:
            if self.gps_frame:
                self.error(f"Unable to obtain {self.base_link_frame} -> {self.gps_frame} transform. Will assume "
                           "navsat device is mounted at robots origin")
            return gps_pose
        r, p, y = to_rpy(self.orientation)
        heading = from_rpy(r, p, y + self.heading_offset())
        return _translation(heading @ offset.trans).inverse() * gps_pose

    def _robot_origin_world(self, gps_world: Rigid, stamp_ns: int) -> Rigid:
        offset = self.lookup(self.base_link_frame, self.gps_frame, stamp_ns)
        if offset is None:
            if self.gps_frame:
                self.error(f"Could not obtain {self.base_link_frame} -> {self.gps_frame} transform. Will not remove "
                           "offset of navsat device from robot's origin.")
            return gps_world
        robot = self.lookup(self.world_frame, self.base_link_frame, stamp_ns)
        if robot is None:
            self.error(f"Could not obtain {self.world_frame} -> {self.base_link_frame} transform. Will not remove "
                       "offset of navsat device from robot's origin")
            return gps_world
        return _translation(robot.rot @ offset.trans).inverse() * gps_world

    def cartesian_to_world(self, cartesian: Rigid) -> np.ndarray:
        """A Cartesian point in the world frame (z zeroed with zero_altitude)."""
        p = (self.cartesian_world * cartesian).trans.copy()
        if self.p.zero_altitude:
            p[2] = 0.0
        return p

    def world_to_geodetic(self, point: np.ndarray) -> tuple[float, float, float]:
        c = (self.world_cartesian * _translation(point)).trans
        if self.local is not None:
            return self.local.reverse(float(c[0]), float(c[1]), float(c[2]))
        lat, lon = nc.from_grid(self.utm_zone, self.north, float(c[0]), float(c[1]))
        return lat, lon, float(c[2])

    def geodetic_to_world(self, lat: float, lon: float, alt: float) -> np.ndarray:
        if self.local is not None:
            x, y, _ = self.local.forward(lat, lon, alt)
        else:
            x, y, *_ = nc.to_grid(lat, lon, self.utm_zone)
        return self.cartesian_to_world(_translation((x, y, alt)))

    # --- outputs ------------------------------------------------------------------------------------------------
    def gps_odometry(self) -> tuple[np.ndarray, np.ndarray, int] | None:
        """(robot origin in the world frame, its 6×6 covariance, stamp) of the newest fix not yet sent."""
        if not (self.transform_good and self.gps_updated and self.odom_updated):
            return None
        gps_world = _translation(self.cartesian_to_world(self.latest_cartesian))
        robot = self._robot_origin_world(gps_world, self.gps_stamp_ns).trans.copy()
        if self.p.zero_altitude:
            robot[2] = 0.0
        r6 = _rot6(self.cartesian_world.rot)
        cov = r6 @ self.latest_cartesian_cov @ r6.T
        self.gps_updated = False
        return robot, cov, self.gps_stamp_ns

    def filtered_fix(self) -> tuple[tuple[float, float, float], np.ndarray, int] | None:
        """(latitude, longitude, altitude) of the newest odometry not yet sent, its 3×3 covariance, stamp."""
        if not (self.transform_good and self.odom_updated):
            return None
        lla = self.world_to_geodetic(self.latest_world.trans)
        r6 = _rot6(self.world_cartesian.rot)
        cov = (r6 @ self.latest_odom_cov @ r6.T)[:3, :3]
        self.odom_updated = False
        return lla, cov, self.odom_stamp_ns
