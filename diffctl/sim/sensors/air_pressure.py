"""air_pressure sensors: gz.msgs.FluidPressure from the sensor's height, as gz-sensors computes it.

The U.S. Standard Atmosphere below 11 km (gz-sensors AirPressureSensor, after RotorS): height h = reference
altitude + the sensor's world z; geopotential height H = R h / (R + h); temperature T = T0 - L H; pressure
p = p0 (T0 / T)^(g M / (R* (-L))). Noise is Gaussian in pascals (a bias drawn once, with a random sign, plus
white noise) and the message's `variance` is sqrt(stddev), exactly what Gazebo writes there.
"""

from __future__ import annotations

import math

import numpy as np

from diffctl.bus import gz
from diffctl.description.model import Sensor
from diffctl.sim.entity import Entity
from diffctl.sim.sensors.common import ScalarNoise, frame_id

GAS_CONSTANT_J_PER_KMOL_K = 8314.32
AIR_MOLAR_MASS_KG_PER_KMOL = 28.9644
GRAVITY_M_PER_S2 = 9.80665
EARTH_RADIUS_M = 6356766.0
SEA_LEVEL_PRESSURE_PA = 101325.0
SEA_LEVEL_TEMPERATURE_K = 288.15
LAPSE_RATE_K_PER_M = 0.0065
_EXPONENT = GRAVITY_M_PER_S2 * AIR_MOLAR_MASS_KG_PER_KMOL / (GAS_CONSTANT_J_PER_KMOL_K * -LAPSE_RATE_K_PER_M)


def pressure_pa(height_m: float) -> float:
    """Static air pressure at `height_m` above sea level."""
    geopotential_m = EARTH_RADIUS_M * height_m / (EARTH_RADIUS_M + height_m)
    temperature_k = SEA_LEVEL_TEMPERATURE_K - LAPSE_RATE_K_PER_M * geopotential_m
    return SEA_LEVEL_PRESSURE_PA * math.exp(_EXPONENT * math.log(SEA_LEVEL_TEMPERATURE_K / temperature_k))


class AirPressure:
    def __init__(self, entity: Entity, sensor: Sensor, rng: np.random.Generator) -> None:
        spec = sensor.air_pressure
        assert spec is not None
        self.entity, self.sensor, self.spec, self.rng = entity, sensor, spec, rng
        self.frame_id = frame_id(entity.name, sensor)
        self._noise = ScalarNoise(spec.noise, rng)

    def sample(self, sim_time_ns: int) -> dict:
        z = self.entity.link_pose(self.sensor.link).compose(self.sensor.pose_link).xyz[2]
        p = pressure_pa(self.spec.reference_altitude_m + z)
        msg = {"header": gz.header(sim_time_ns, self.frame_id), "pressure": self._noise.apply(p)}
        if self.spec.noise.active and self.spec.noise.type.startswith("gaussian"):
            msg["variance"] = math.sqrt(self.spec.noise.stddev)
        return msg
