"""Sensors in a running simulation on a real router: Gazebo's default topic names from the world, a camera
that renders only once someone subscribes, and one warning for each sensor type that is not simulated."""

from __future__ import annotations

import threading

import numpy as np
import pytest
from sim_helpers import sdf_world

from diffctl.bus import gz, open_session
from diffctl.sim.runner import Simulation
from diffctl.sim.sensors import CameraSensor
from diffctl.sim.sensors.depth import unpack_points
from tests.waiting import wait_for

WORLD = sdf_world(
    """<model name="wall"><static>true</static><pose>2 0 0.5 0 0 0</pose><link name="l">
      <visual name="v"><geometry><box><size>0.2 1 1</size></box></geometry></visual></link></model>
    <model name="rig"><static>true</static><pose>0 0 0.5 0 0 0</pose><link name="body">
      <sensor name="eye" type="rgbd_camera"><update_rate>20</update_rate>
        <camera><horizontal_fov>1.047</horizontal_fov><image><width>80</width><height>60</height></image>
          <clip><near>0.1</near><far>10</far></clip></camera></sensor>
      <sensor name="bump" type="contact"><contact><collision>c</collision></contact></sensor>
      <sensor name="heat" type="thermal_camera"/>
    </link></model>""",
    name="shop",
)
BASE = "/world/shop/model/rig/link/body/sensor/eye"


@pytest.mark.slow
def test_rgbd_camera_publishes_on_gazebos_default_topics_on_demand(router: str, capfd: pytest.CaptureFixture) -> None:
    session = open_session()
    sim = Simulation(WORLD, rtf=0.0, paused=False, session=session)
    stop = threading.Event()
    thread = threading.Thread(target=sim.run, args=(stop,), daemon=True)
    subs = []
    try:
        warned = [line for line in capfd.readouterr().err.splitlines() if "[WARN]" in line]
        assert any("model 'rig'" in ln and "sensor 'bump' of type 'contact'" in ln for ln in warned), warned
        assert any("model 'rig'" in ln and "thermal camera 'heat' on link" in ln for ln in warned), warned
        cam = next(s for s in sim.models["rig"].sensors if isinstance(s, CameraSensor))
        thread.start()
        assert wait_for(lambda: sim.stepper.sim_time_ns > 500_000_000, 30)
        assert cam.frames == 0  # nobody subscribed: nothing rendered

        got: dict[str, list[dict]] = {"points": [], "camera_info": []}
        for name, samples in got.items():
            subs.append(
                session.declare_subscriber(
                    gz.key(f"{BASE}/{name}"), lambda s, out=samples: out.append(gz.decode(s.payload.to_bytes())[1])
                )
            )
        assert wait_for(lambda: len(got["points"]) >= 2 and len(got["camera_info"]) >= 2, 30)
        cloud, info = got["points"][-1], got["camera_info"][-1]
        assert (cloud["width"], cloud["height"], cloud["point_step"]) == (80, 60, 24)
        assert gz.header_value(cloud["header"], "frame_id") == "rig::body::eye"
        xyz, _ = unpack_points(cloud["data"])
        hit = np.isfinite(xyz[:, 0])
        assert hit.any() and np.allclose(xyz[hit, 0], 1.9, atol=0.01)  # the wall's face, 1.9 m ahead
        assert info["intrinsics"]["k"][2] == 40.0 and info["width"] == 80

        for s in subs:
            s.undeclare()
        subs.clear()
        assert wait_for(lambda: not any(p.matched for p in sim.models["rig"].publishers), 10)
        frames = cam.frames
        t = sim.stepper.sim_time_ns
        assert wait_for(lambda: sim.stepper.sim_time_ns > t + 500_000_000, 30)
        assert cam.frames == frames  # nobody listens any more: no rendering
    finally:
        for s in subs:
            s.undeclare()
        stop.set()
        thread.join(5)
        sim.close()
        session.close()
