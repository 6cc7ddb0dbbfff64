"""CPU sensors as Gazebo Harmonic's sensors system produces them: lidar by ray casting, IMU from link
velocities, magnetometer from the world's field, air pressure from height, navsat from the world's spherical
coordinates, camera / depth_camera / rgbd_camera by PyBullet's TinyRenderer, rendered only on demand.

Each sensor reads the physics world when asked and returns gz.msgs messages as dicts (gz-msgs .proto field
names, bytes fields as raw `bytes`); topics (topics.py) and scheduling (camera_task.py, the runner) are
separate from the sampling. All randomness comes from each sensor's own seeded numpy Generator.
"""

from diffctl.sim.sensors.air_pressure import AirPressure
from diffctl.sim.sensors.camera import Camera, Frame
from diffctl.sim.sensors.camera_sensor import CameraSensor
from diffctl.sim.sensors.camera_task import CameraTask
from diffctl.sim.sensors.imu import Imu, ImuNoise, point_velocity, specific_force
from diffctl.sim.sensors.lidar import MAX_RAYS, Lidar, lidar_directions, ranges_from_hits
from diffctl.sim.sensors.magnetometer import Magnetometer
from diffctl.sim.sensors.navsat import NavSat, origin_problem
from diffctl.sim.sensors.rate import RenderRate

__all__ = [
    "MAX_RAYS",
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
