"""A camera renders for its image subscribers only: the shipped bridge config keeps the camera's camera_info
subscribed all the time (as ros_gz_bridge does), yet nothing is rendered until ROS asks for frames.

Real router, the real car in the real empty world, the bridge with config/bridge_config.yaml."""

from __future__ import annotations

import subprocess
import threading

import pytest

from diffctl.bus import open_session
from diffctl.description.sdf_loader import load_model, load_world
from diffctl.sim.runner import Simulation
from diffctl.sim.sensors import CameraSensor
from tests.conftest import Procs
from tests.probe import Probe
from tests.sim.sim_helpers import CAR, EMPTY_WORLD, REPO
from tests.waiting import wait_for


@pytest.mark.slow
def test_camera_info_flows_without_rendering_and_frames_follow_image_subscribers(router: str, procs: Procs) -> None:
    session = open_session()
    world = load_world(EMPTY_WORLD)
    sim = Simulation(world, rtf=0.0, paused=False, session=session)
    stop = threading.Event()
    thread = threading.Thread(target=sim.run, args=(stop,), daemon=True)
    user = Probe("viewer")
    try:
        sim.spawn(load_model(CAR, name="robot"))
        thread.start()
        (cam,) = [s for s in sim.models["robot"].sensors if isinstance(s, CameraSensor)]
        # The bridge as users run it: its own process (in this one, Zenoh's locality would hide the sim from it).
        procs.diffctl("bridge", "--config", str(REPO / "config" / "bridge_config.yaml"), stdout=subprocess.DEVNULL)

        infos: list = []
        user.create_subscription("/camera/camera_info", "sensor_msgs/msg/CameraInfo", infos.append)
        assert wait_for(lambda: len(infos) >= 3, 60)
        info = infos[-1]
        assert (info.width, info.height, info.header.frame_id) == (320, 240, "camera_link")
        assert cam.frames == 0  # camera_info is kept subscribed, and costs no render

        images: list = []
        sub = user.create_subscription("/camera/image_raw", "sensor_msgs/msg/Image", images.append)
        assert wait_for(lambda: len(images) >= 2, 60)
        assert cam.frames >= 2 and (images[-1].width, images[-1].height) == (info.width, info.height)

        sub.close()
        image_pub = next(p for p in sim.models["robot"].publishers if p.topic == "/camera")
        assert wait_for(lambda: not image_pub.matched, 30)
        frames, t = cam.frames, sim.stepper.sim_time_ns
        seen = len(infos)
        assert wait_for(lambda: sim.stepper.sim_time_ns > t + 1_000_000_000 and len(infos) > seen + 2, 60)
        assert cam.frames == frames  # nobody wants frames any more: camera_info goes on, rendering stops
    finally:
        user.close()
        stop.set()
        thread.join(5)
        sim.close()
        session.close()
