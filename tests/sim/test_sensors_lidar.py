"""gpu_lidar's two outputs from one scan in a real PyBullet world: the LaserScan and the packed points."""

from __future__ import annotations

import numpy as np
from sim_helpers import build, sdf_world

from diffctl.sim.sensors import RAYS_PER_BATCH, Lidar
from diffctl.sim.sensors.lidar import lidar_points

LIDAR = """<model name="rig"><static>true</static><pose>0 0 0.5 0 0 1.0</pose><link name="l">
  <sensor name="scanner" type="gpu_lidar"><topic>scan</topic><update_rate>10</update_rate><lidar>
    <scan><horizontal><samples>90</samples><min_angle>-0.8</min_angle><max_angle>0.8</max_angle></horizontal>
      <vertical><samples>3</samples><min_angle>-0.1</min_angle><max_angle>0.1</max_angle></vertical></scan>
    <range><min>0.05</min><max>8</max></range></lidar></sensor></link></model>"""
# A wall 2 m ahead of the lidar (which faces yaw 1.0), 1 m wide: some rays hit, the outer ones miss.
WALL = """<model name="wall"><static>true</static><pose>{x} {y} 0.5 0 0 1.0</pose><link name="l">
  <collision name="c"><geometry><box><size>0.2 1 1</size></box></geometry></collision></link></model>"""


def test_a_scan_denser_than_one_pybullet_ray_batch_is_cast_whole() -> None:
    # 200 x 100 = 20,000 rays: past PyBullet's 16,384 a rayTestBatch; Gazebo has no such cap (a 3D lidar such as
    # a MID-360 model asks for 36,000). Every row, the last batch's too, must see the wall where it is.
    x, y = 2.1 * np.cos(1.0), 2.1 * np.sin(1.0)
    dense = LIDAR.replace("<samples>90</samples>", "<samples>200</samples>").replace(
        "<samples>3</samples>", "<samples>100</samples>")
    pw, ents = build(sdf_world(dense + WALL.format(x=x, y=y)))
    try:
        lidar = Lidar(ents["rig"], next(ents["rig"].model.sensors()), np.random.default_rng(0))
        assert lidar.count == 20_000 > RAYS_PER_BATCH
        ranges = lidar.scan().reshape(100, 200)
        pts = lidar_points(ranges.ravel(), lidar.directions).reshape(100, 200, 3)
        hit = np.isfinite(ranges)
        assert hit.any(axis=1).all() and not hit.all(axis=1).any()  # each row hits the wall and misses beside it
        assert np.allclose(pts[hit][:, 0], 2.0, atol=0.01)  # the wall's face: x = 2 m in the sensor frame
        assert (hit.sum(axis=1) == hit[0].sum()).all()  # the wall is as wide in every row, first batch or last
    finally:
        pw.close()


def test_scan_and_points_from_one_scan() -> None:
    x, y = 2.1 * np.cos(1.0), 2.1 * np.sin(1.0)
    pw, ents = build(sdf_world(LIDAR + WALL.format(x=x, y=y)))
    try:
        lidar = Lidar(ents["rig"], next(ents["rig"].model.sensors()), np.random.default_rng(0))
        msgs = lidar.messages(2_000_000_000, {"scan", "points"})
        scan, cloud = msgs["scan"], msgs["points"]
        assert (cloud["width"], cloud["height"], cloud["point_step"], cloud["row_step"]) == (90, 3, 32, 32 * 90)
        assert [(f["name"], f["offset"], f["datatype"]) for f in cloud["field"]] == [
            ("x", 0, "FLOAT32"),
            ("y", 4, "FLOAT32"),
            ("z", 8, "FLOAT32"),
            ("intensity", 16, "FLOAT32"),
            ("ring", 24, "UINT16"),
        ]
        dtype = np.dtype({"names": ["x", "y", "z", "ring"], "formats": ["<f4", "<f4", "<f4", "<u2"],
                          "offsets": [0, 4, 8, 24], "itemsize": 32})  # fmt: skip
        pts = np.frombuffer(cloud["data"], dtype=dtype)
        assert pts["ring"].reshape(3, 90).tolist() == [[0] * 90, [1] * 90, [2] * 90]
        hit = np.isfinite(pts["x"])
        assert 10 < hit.sum() < 270 and not cloud["is_dense"]
        # In the sensor frame the wall's face is the plane x = 2 m.
        assert np.allclose(pts["x"][hit], 2.0, atol=0.01) and np.all(np.abs(pts["y"][hit]) <= 0.5)
        # The same scan: each point's distance is its ray's range.
        ranges = np.array(scan["ranges"])
        norms = np.sqrt(pts["x"] ** 2 + pts["y"] ** 2 + pts["z"] ** 2)
        assert np.allclose(norms[hit], ranges[hit], atol=1e-3) and np.all(np.isinf(ranges[~hit]))
        assert scan["count"] == 90 and scan["vertical_count"] == 3
        assert lidar.messages(0, set()) == {}
    finally:
        pw.close()
