"""navsat sensors: gz.msgs.NavSat from the sensor's place in a world with `<spherical_coordinates>`.

As gz-sim's NavSat system with gz-math's SphericalCoordinates (WGS84): the sensor's world position, taken as
east-north-up about the world origin after turning by `<heading_deg>`, goes to Earth-centred coordinates and
from there to latitude, longitude and height above the ellipsoid (Bowring's single-step formula, as gz-math).
The velocity is the sensor point's world velocity (gz-sim reports it as east, north, up). Noise: gz-sensors
adds horizontal position noise to latitude and longitude in degrees, vertical in metres, velocity noise in m/s.
Without `<spherical_coordinates>` Gazebo has no position to give, and publishes nothing.
"""

from __future__ import annotations

import math

import numpy as np

from diffctl.bus import gz
from diffctl.description.model import Sensor, SphericalCoordinates
from diffctl.sim.entity import Entity
from diffctl.sim.sensors.common import ScalarNoise, frame_id

WGS84_A_M = 6378137.0
WGS84_B_M = 6356752.314245
_E2 = 1.0 - WGS84_B_M**2 / WGS84_A_M**2  # first eccentricity, squared
_EP2 = WGS84_A_M**2 / WGS84_B_M**2 - 1.0  # second eccentricity, squared


def geodetic_to_ecef(lat_rad: float, lon_rad: float, height_m: float) -> np.ndarray:
    n = WGS84_A_M / math.sqrt(1.0 - _E2 * math.sin(lat_rad) ** 2)
    return np.array(
        [
            (n + height_m) * math.cos(lat_rad) * math.cos(lon_rad),
            (n + height_m) * math.cos(lat_rad) * math.sin(lon_rad),
            (n * (1.0 - _E2) + height_m) * math.sin(lat_rad),
        ]
    )


def ecef_to_geodetic(p: np.ndarray) -> tuple[float, float, float]:
    """(latitude rad, longitude rad, height m) by Bowring's formula."""
    x, y, z = float(p[0]), float(p[1]), float(p[2])
    r = math.hypot(x, y)
    theta = math.atan2(z * WGS84_A_M, r * WGS84_B_M)
    lat = math.atan2(z + _EP2 * WGS84_B_M * math.sin(theta) ** 3, r - _E2 * WGS84_A_M * math.cos(theta) ** 3)
    n = WGS84_A_M / math.sqrt(1.0 - _E2 * math.sin(lat) ** 2)
    return lat, math.atan2(y, x), r / math.cos(lat) - n


def enu_to_ecef_rotation(lat_rad: float, lon_rad: float) -> np.ndarray:
    """Columns: east, north and up at (lat, lon), in Earth-centred coordinates."""
    sl, cl, so, co = math.sin(lat_rad), math.cos(lat_rad), math.sin(lon_rad), math.cos(lon_rad)
    return np.array([[-so, -co * sl, co * cl], [co, -so * sl, so * cl], [0.0, cl, sl]])


def world_to_geodetic(origin: SphericalCoordinates, xyz_m: tuple[float, float, float]) -> tuple[float, float, float]:
    """(latitude deg, longitude deg, altitude m) of a world point."""
    lat0, lon0 = math.radians(origin.latitude_deg), math.radians(origin.longitude_deg)
    # gz-math negates the heading for compatibility (a positive heading turned the world clockwise).
    h = -math.radians(origin.heading_deg)
    x, y, z = xyz_m
    enu = np.array([x * math.cos(h) + y * math.sin(h), -x * math.sin(h) + y * math.cos(h), z])
    ecef = geodetic_to_ecef(lat0, lon0, origin.elevation_m) + enu_to_ecef_rotation(lat0, lon0) @ enu
    lat, lon, alt = ecef_to_geodetic(ecef)
    return math.degrees(lat), math.degrees(lon), alt


def _wrap_deg(angle_deg: float) -> float:
    """Into [-180, 180], as gz::math::Angle::Normalize."""
    return math.degrees(math.atan2(math.sin(math.radians(angle_deg)), math.cos(math.radians(angle_deg))))


class NavSat:
    def __init__(self, entity: Entity, sensor: Sensor, rng: np.random.Generator, origin: SphericalCoordinates) -> None:
        spec = sensor.navsat
        assert spec is not None
        self.entity, self.sensor, self.origin = entity, sensor, origin
        self.frame_id = frame_id(entity.name, sensor)
        self._pos_h = ScalarNoise(spec.horizontal_position_noise, rng)
        self._pos_v = ScalarNoise(spec.vertical_position_noise, rng)
        self._vel_h = ScalarNoise(spec.horizontal_velocity_noise, rng)
        self._vel_v = ScalarNoise(spec.vertical_velocity_noise, rng)

    def sample(self, sim_time_ns: int) -> dict:
        pose = self.entity.link_pose(self.sensor.link).compose(self.sensor.pose_link)
        lat, lon, alt = world_to_geodetic(self.origin, pose.xyz)
        v, _ = self.entity.link_velocity(self.sensor.link, pose.xyz)
        return {
            "header": gz.header(sim_time_ns, self.frame_id),
            "latitude_deg": _wrap_deg(self._pos_h.apply(lat)),
            "longitude_deg": _wrap_deg(self._pos_h.apply(lon)),
            "altitude": self._pos_v.apply(alt),
            "velocity_east": self._vel_h.apply(v[0]),
            "velocity_north": self._vel_h.apply(v[1]),
            "velocity_up": self._vel_v.apply(v[2]),
            "frame_id": self.frame_id,
        }


def origin_problem(origin: SphericalCoordinates | None) -> str | None:
    """Why a navsat in a world with `origin` cannot publish, or None."""
    if origin is None:
        return "the world has no <spherical_coordinates>, so it publishes nothing (as in Gazebo)"
    if origin.surface_model != "EARTH_WGS84":
        return (
            f"<surface_model> {origin.surface_model!r} is not simulated (simulated: EARTH_WGS84); it publishes nothing"
        )
    if origin.world_frame_orientation != "ENU":
        return f"<world_frame_orientation> {origin.world_frame_orientation!r} is not supported (valid: ENU)"
    return None
