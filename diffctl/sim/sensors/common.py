"""What every simulated sensor shares: its header frame id and its pose in gz.msgs form."""

from __future__ import annotations

from diffctl.description.model import Sensor
from diffctl.description.pose import Pose


def frame_id(model_name: str, sensor: Sensor) -> str:
    """Gazebo's header frame id: `<gz_frame_id>` (or the older `<frame_id>`), else the scoped sensor name
    without the world, `model::link::sensor` (gz-sensors Sensor.cc)."""
    return sensor.frame_id or f"{model_name}::{sensor.link}::{sensor.name}"


def pose_msg(p: Pose) -> dict:
    return {
        "position": {"x": p.xyz[0], "y": p.xyz[1], "z": p.xyz[2]},
        "orientation": {"x": p.quat[0], "y": p.quat[1], "z": p.quat[2], "w": p.quat[3]},
    }


def rotation(p: Pose) -> list[list[float]]:
    """The 3x3 rotation of `p`."""
    return [row[:3] for row in p.to_matrix()[:3]]
