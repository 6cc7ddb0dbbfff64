"""Sensor details community robots rely on: LaserScan intensities one per range (through the bridge's
conversion too), a thermal camera named in one clear warning, and a camera's <triggered>/<trigger_topic>."""

from __future__ import annotations

import numpy as np
from sim_helpers import build, sdf_world
from test_sensors_lidar import LIDAR

from diffctl.bridge import type_pairs
from diffctl.bus import gz
from diffctl.description.sdf_loader import parse_model
from diffctl.sim.sensors import Lidar


def test_a_scan_has_one_intensity_per_range_zero_without_retro_reflectors() -> None:
    pw, ents = build(sdf_world(LIDAR))
    try:
        lidar = Lidar(ents["rig"], next(ents["rig"].model.sensors()), np.random.default_rng(0))
        scan = lidar.messages(1_000_000_000, {"scan"})["scan"]
        _, wire = gz.decode(gz.encode("gz.msgs.LaserScan", scan))
        assert len(wire["intensities"]) == len(wire["ranges"]) == 90 * 3
        assert not np.asarray(wire["intensities"]).any()
        ros = type_pairs.lookup("sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan").convert_to_ros(wire)
        assert len(ros.intensities) == len(ros.ranges) == 90  # the middle layer, as ros_gz_bridge
    finally:
        pw.close()


def _camera_model(camera_extra: str, sensor_type: str = "camera") -> str:
    return f"""<?xml version="1.0"?><sdf version="1.9"><model name="m"><static>true</static><link name="l">
      <sensor name="cam" type="{sensor_type}"><topic>cam/image</topic><update_rate>5</update_rate>
        <camera><image><width>64</width><height>48</height></image>{camera_extra}</camera></sensor>
    </link></model></sdf>"""


def test_triggered_camera_and_its_trigger_topic_are_read() -> None:
    plain = next(parse_model(_camera_model("")).sensors())
    assert plain.camera is not None and not plain.camera.triggered and plain.camera.trigger_topic == ""
    trig = next(parse_model(_camera_model("<triggered>true</triggered>")).sensors())
    assert trig.camera is not None and trig.camera.triggered and trig.camera.trigger_topic == ""
    named = next(parse_model(_camera_model("<triggered>1</triggered><trigger_topic>shoot</trigger_topic>")).sensors())
    assert named.camera is not None and named.camera.trigger_topic == "/shoot"


def test_a_thermal_camera_is_one_clear_line_naming_it() -> None:
    model = parse_model(_camera_model("", "thermal_camera"))
    assert list(model.sensors()) == []
    (line,) = model.ignored
    assert "thermal camera 'cam' on link 'l'" in line and "not simulated" in line
