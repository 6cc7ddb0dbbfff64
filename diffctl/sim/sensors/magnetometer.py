"""magnetometer sensors: gz.msgs.Magnetometer, the world's <magnetic_field> seen in the sensor frame, as
gz-sensors' MagnetometerSensor computes it when the world has no <spherical_coordinates>: the field rotated by
the inverse of the sensor's world orientation, plus each axis's noise (tesla), in `field_tesla`.

With spherical coordinates Gazebo instead looks the field up in its own table of the Earth's field (in gauss,
NED by default); diffctl keeps the world's field then too.
"""

from __future__ import annotations

import numpy as np

from diffctl.bus import gz
from diffctl.description.model import Sensor
from diffctl.description.pose import Vec3
from diffctl.sim.entity import Entity
from diffctl.sim.sensors.common import ScalarNoise, frame_id


class Magnetometer:
    def __init__(self, entity: Entity, sensor: Sensor, field_world_t: Vec3, rng: np.random.Generator) -> None:
        spec = sensor.magnetometer
        assert spec is not None
        self.entity, self.sensor, self.field_world_t = entity, sensor, field_world_t
        self.frame_id = frame_id(entity.name, sensor)
        self._noise = tuple(ScalarNoise(n, rng) for n in spec.noise)

    def field_in_sensor_t(self) -> Vec3:
        pose = self.entity.link_pose(self.sensor.link).compose(self.sensor.pose_link)
        return pose.inverse().rotate(self.field_world_t)

    def sample(self, sim_time_ns: int) -> dict:
        local = self.field_in_sensor_t()
        x, y, z = (noise.apply(v) for noise, v in zip(self._noise, local, strict=True))
        return {"header": gz.header(sim_time_ns, self.frame_id), "field_tesla": {"x": x, "y": y, "z": z}}
