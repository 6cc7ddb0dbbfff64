"""magnetometer sensors: gz.msgs.Magnetometer, the world's <magnetic_field> seen in the sensor frame, as
gz-sensors' MagnetometerSensor computes it when the world has no <spherical_coordinates>: the field rotated by
the inverse of the sensor's world orientation, plus each axis's noise (tesla), in `field_tesla`.

With spherical coordinates gz-sim's Magnetometer system replaces that field, at every update, by the Earth's at
the sensor's latitude and longitude (earth_field.py): in gauss and north/east/down by default, or tesla and
east/north/up with the system's `<use_units_gauss>false` / `<use_earth_frame_ned>false`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from diffctl.bus import gz
from diffctl.description.model import Sensor, SphericalCoordinates
from diffctl.description.pose import Vec3
from diffctl.sim.entity import Entity
from diffctl.sim.sensors.common import ScalarNoise, frame_id
from diffctl.sim.sensors.earth_field import earth_field
from diffctl.sim.sensors.navsat import world_to_geodetic


@dataclass(frozen=True)
class EarthFieldParams:
    """Where the world is on the Earth, and the Magnetometer system's `use_units_gauss`, `use_earth_frame_ned`."""

    origin: SphericalCoordinates
    units_gauss: bool = True
    ned: bool = True


class Magnetometer:
    def __init__(
        self,
        entity: Entity,
        sensor: Sensor,
        field_world_t: Vec3,
        rng: np.random.Generator,
        earth: EarthFieldParams | None = None,
    ) -> None:
        spec = sensor.magnetometer
        assert spec is not None
        self.entity, self.sensor, self.field_world_t, self.earth = entity, sensor, field_world_t, earth
        self.frame_id = frame_id(entity.name, sensor)
        self._noise = tuple(ScalarNoise(n, rng) for n in spec.noise)

    def field_in_sensor_t(self) -> Vec3:
        pose = self.entity.link_pose(self.sensor.link).compose(self.sensor.pose_link)
        field = self.field_world_t
        if self.earth is not None:
            lat_deg, lon_deg, _ = world_to_geodetic(self.earth.origin, pose.xyz)
            field = earth_field(lat_deg, lon_deg, self.earth.units_gauss, self.earth.ned)
        return pose.inverse().rotate(field)

    def sample(self, sim_time_ns: int) -> dict:
        local = self.field_in_sensor_t()
        x, y, z = (noise.apply(v) for noise, v in zip(self._noise, local, strict=True))
        return {"header": gz.header(sim_time_ns, self.frame_id), "field_tesla": {"x": x, "y": y, "z": z}}
