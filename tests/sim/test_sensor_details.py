"""Sensor details community robots rely on: LaserScan intensities one per range (through the bridge's
conversion too), a thermal camera named in one clear warning, and a camera's <triggered>/<trigger_topic>."""

from __future__ import annotations

import numpy as np
import pytest
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


MAG_RIG = """<model name="rig"><static>true</static><pose>1 2 0.5 0 0 {yaw}</pose><link name="l">
  <sensor name="compass" type="magnetometer"><topic>mag</topic><update_rate>50</update_rate>
    <magnetometer><x><noise type="gaussian"><mean>0</mean><stddev>1e-8</stddev></noise></x></magnetometer>
  </sensor></link></model>"""


def test_a_magnetometer_reads_the_worlds_field_in_its_own_frame() -> None:
    yaw = 0.9
    world = sdf_world("<magnetic_field>6e-06 2.3e-05 -4.2e-05</magnetic_field>" + MAG_RIG.format(yaw=yaw))
    assert world.physics.magnetic_field_t == (6e-06, 2.3e-05, -4.2e-05)
    pw, ents = build(world)
    try:
        from diffctl.sim.sensors import Magnetometer

        sensor = next(ents["rig"].model.sensors())
        assert sensor.type == "magnetometer" and sensor.magnetometer is not None
        mag = Magnetometer(ents["rig"], sensor, world.physics.magnetic_field_t, np.random.default_rng(1))
        msg = mag.sample(1_000_000)
        bx, by, bz = 6e-06, 2.3e-05, -4.2e-05
        # a frame turned by yaw about z sees the world vector turned by -yaw
        expected = (np.cos(yaw) * bx + np.sin(yaw) * by, -np.sin(yaw) * bx + np.cos(yaw) * by, bz)
        f = msg["field_tesla"]
        assert f["x"] == pytest.approx(expected[0], abs=1e-7)  # x carries 1e-8 T of noise
        assert (f["y"], f["z"]) == pytest.approx(expected[1:], abs=1e-12)
        assert gz.header_value(msg["header"], "frame_id") == "rig::l::compass"
    finally:
        pw.close()
