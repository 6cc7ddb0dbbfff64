"""A lidar scan crosses the gz encoding as a raw float64 array and reaches ROS unrounded, ±inf intact.

Real PyBullet rays, the real gz codec, the bridge's real LaserScan conversion and the Jazzy CDR serializer."""

from __future__ import annotations

import math

import numpy as np
from sim_helpers import build, sdf_world

from diffctl.bridge import type_pairs
from diffctl.bus import gz
from diffctl.interfaces import types
from diffctl.sim.sensors import Lidar

RIG = """<model name="rig"><static>true</static><pose>0 0 0.5 0 0 0</pose><link name="l">
  <sensor name="scanner" type="gpu_lidar"><topic>scan</topic><update_rate>10</update_rate><lidar>
    <scan><horizontal><samples>181</samples><min_angle>-1.2</min_angle><max_angle>1.2</max_angle></horizontal></scan>
    <range><min>0.05</min><max>8</max></range></lidar></sensor></link></model>
<model name="wall"><static>true</static><pose>2.1 0 0.5 0 0 0</pose><link name="l">
  <collision name="c"><geometry><box><size>0.2 2 1</size></box></geometry></collision></link></model>"""


def test_ranges_travel_as_raw_doubles_to_ros() -> None:
    pw, ents = build(sdf_world(RIG))
    try:
        lidar = Lidar(ents["rig"], next(ents["rig"].model.sensors()), np.random.default_rng(0))
        ranges = lidar.scan()
        _, fields = gz.decode(gz.encode("gz.msgs.LaserScan", lidar.scan_msg(1_000_000_000, ranges)))
    finally:
        pw.close()
    sent = fields["ranges"]
    assert isinstance(sent, np.ndarray) and sent.dtype == np.float64
    np.testing.assert_array_equal(sent, ranges)  # bit for bit: no rounding on the way
    hit = np.isfinite(sent)
    assert 0 < hit.sum() < len(sent) and np.all(np.isposinf(sent[~hit]))
    # The wall's face is the plane x = 2 m: each ray's range is 2 / cos(angle), beyond 0.1 mm precision.
    angles = -1.2 + np.arange(181) * (2.4 / 180)
    assert np.allclose(sent[hit], 2.0 / np.cos(angles[hit]), atol=1e-6)
    assert np.any(np.abs(sent[hit] * 1e4 - np.round(sent[hit] * 1e4)) > 1e-3)

    pair = type_pairs.lookup("sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan")
    msg = types.deserialize(
        types.serialize(pair.convert_to_ros(fields), "sensor_msgs/msg/LaserScan"), "sensor_msgs/msg/LaserScan"
    )
    np.testing.assert_array_equal(msg.ranges, sent.astype(np.float32))
    assert msg.angle_increment == np.float32(2.4 / 180) and math.isinf(msg.ranges[0]) == (not hit[0])


RETRO = RIG.replace(
    "<collision name=\"c\"><geometry><box><size>0.2 2 1</size></box></geometry></collision></link></model>",
    "<collision name=\"c\"><geometry><box><size>0.2 2 1</size></box></geometry></collision>"
    "<visual name=\"v\"><geometry><box><size>0.2 2 1</size></box></geometry><laser_retro>1150</laser_retro></visual>"
    "</link></model>",
) + """<model name="plain"><static>true</static><pose>0 -2.1 0.5 0 0 0</pose><link name="l">
  <collision name="c"><geometry><box><size>2 0.2 1</size></box></geometry></collision>
  <visual name="v"><geometry><box><size>2 0.2 1</size></box></geometry></visual></link></model>"""


def test_intensities_are_the_laser_retro_of_the_visual_hit_as_gz_reports_them() -> None:
    from diffctl.sim.runner import Simulation
    from diffctl.sim.sensors.lidar import POINTS, SCAN

    sim = Simulation(sdf_world(RETRO.replace("-1.2", "-3.1").replace("1.2<", "0.0<")), rtf=0.0)
    try:
        lidar = next(s for s in sim.models["rig"].sensors if isinstance(s, Lidar))
        out = lidar.messages(1_000_000_000, {SCAN, POINTS})
    finally:
        sim.close()
    _, scan = gz.decode(gz.encode("gz.msgs.LaserScan", out[SCAN]))
    ranges, intensities = np.asarray(scan["ranges"]), np.asarray(scan["intensities"])
    assert len(intensities) == len(ranges) == 181
    angles = -3.1 + np.arange(181) * (3.1 / 180)
    on_wall = np.isfinite(ranges) & (np.abs(angles) < 0.5)  # straight ahead: the retro-reflecting wall
    on_plain = np.isfinite(ranges) & (np.abs(angles + math.pi / 2) < 0.5)  # to the right: no laser_retro
    assert on_wall.any() and on_plain.any()
    assert np.all(intensities[on_wall] == 1150.0) and np.all(intensities[on_plain] == 0.0)
    assert np.all(intensities[~np.isfinite(ranges)] == 0.0)  # a miss reports 0
    from diffctl.sim.sensors.lidar import _LIDAR_DTYPE

    cloud = np.frombuffer(out[POINTS]["data"], dtype=_LIDAR_DTYPE)
    assert np.array_equal(cloud["intensity"], intensities.astype(np.float32))
    ros = type_pairs.lookup("sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan").convert_to_ros(scan)
    assert list(ros.intensities[on_wall][:3]) == [1150.0] * 3
