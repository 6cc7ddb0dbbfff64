"""The shipped bridge configs carry the camera's CameraInfo from the topic the simulator really publishes it on."""

from __future__ import annotations

import pytest

from diffctl.bridge import type_pairs
from diffctl.bridge.config import Direction, load_config
from diffctl.description.sdf_loader import load_model
from diffctl.sim.sensors import topics
from tests.sim.sim_helpers import CAR, CAR_CONTROL, REPO


@pytest.mark.parametrize(
    ("config", "description"),
    [("bridge_config.yaml", CAR), ("bridge_config_control.yaml", CAR_CONTROL)],
)
def test_camera_info_is_bridged_from_the_simulators_topic(config: str, description: object) -> None:
    model = load_model(description, name="robot")
    (camera,) = [s for s in model.sensors() if s.type == "camera"]
    outputs = {o.name: o for o in topics.outputs(camera, topics.base_topic(camera, "empty", "robot"))}
    by_gz = {e.gz_topic: e for e in load_config(REPO / "config" / config)}
    image, info = by_gz[outputs[topics.IMAGE].topic], by_gz[outputs[topics.INFO].topic]
    assert info.gz_type == outputs[topics.INFO].gz_type == "gz.msgs.CameraInfo"
    assert info.ros_type == "sensor_msgs/msg/CameraInfo"
    assert info.direction is Direction.GZ_TO_ROS
    # ROS convention: the calibration sits beside the image, in the same namespace.
    assert info.ros_topic.rsplit("/", 1)[0] == image.ros_topic.rsplit("/", 1)[0]
    assert type_pairs.lookup(info.ros_type, info.gz_type) is not None
