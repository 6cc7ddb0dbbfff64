"""CPU sensors as Gazebo Harmonic's sensors system produces them: lidar by ray casting, IMU from link
velocities, magnetometer from the world's field, air pressure from height, navsat from the world's spherical
coordinates, camera / depth_camera / rgbd_camera by PyBullet's TinyRenderer, rendered only on demand.

Each sensor reads the physics world when asked and returns gz.msgs messages as dicts (gz-msgs .proto field
names, bytes fields as raw `bytes`); topics (topics.py) and scheduling (camera_task.py, the runner) are
separate from the sampling. All randomness comes from each sensor's own seeded numpy Generator.
"""

import importlib
from typing import TYPE_CHECKING, Any

from diffctl.sim.sensors.camera import Camera, Frame
from diffctl.sim.sensors.camera_sensor import CameraSensor
from diffctl.sim.sensors.camera_task import CameraTask
from diffctl.sim.sensors.imu import Imu, ImuNoise, point_velocity, specific_force
from diffctl.sim.sensors.lidar import RAYS_PER_BATCH, Lidar, lidar_directions, ranges_from_hits
from diffctl.sim.sensors.rate import RenderRate

if TYPE_CHECKING:
    from diffctl.sim.sensors.air_pressure import AirPressure
    from diffctl.sim.sensors.magnetometer import Magnetometer
    from diffctl.sim.sensors.navsat import NavSat, origin_problem

# The sensors few robots carry are imported when first asked for (every simulator's start paid for them).
_LATER = {"AirPressure": "air_pressure", "Magnetometer": "magnetometer", "NavSat": "navsat",
          "origin_problem": "navsat"}


def __getattr__(name: str) -> Any:
    if name in _LATER:
        return getattr(importlib.import_module(f"{__name__}.{_LATER[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

__all__ = [
    "RAYS_PER_BATCH",
    "AirPressure",
    "Camera",
    "CameraSensor",
    "CameraTask",
    "Frame",
    "Imu",
    "ImuNoise",
    "Lidar",
    "Magnetometer",
    "NavSat",
    "RenderRate",
    "lidar_directions",
    "origin_problem",
    "point_velocity",
    "ranges_from_hits",
    "specific_force",
]
