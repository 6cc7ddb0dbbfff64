"""The camera: what it sees matches TinyRenderer's own drawing, and it renders only while someone subscribes."""

from __future__ import annotations

import itertools
import threading
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from sim_helpers import CAR, EMPTY_WORLD, box, sdf_world

from diffctl.bus import gz
from diffctl.description.pose import Pose
from diffctl.description.sdf_loader import load_model, load_world
from diffctl.sim.sensors import Camera, CameraSensor
from diffctl.sim.world import PhysicsWorld
from diffctl.viz.png import encode_png


def _scene(gui_planes: bool) -> tuple[PhysicsWorld, Any]:
    world = load_world(EMPTY_WORLD)
    pw = PhysicsWorld(world.physics)
    pw.gui = gui_planes  # build plane visuals for TinyRenderer, as the GUI does, without opening a window
    for m in world.models:
        pw.add_model(m)
    for m in sdf_world(box("tall", 3, 0.5, 0.5, 1, 1, 1) + box("low", 1.2, -0.4, 0.05, 0.3, 0.3, 0.1)).models:
        pw.add_model(m)
    car = pw.add_model(load_model(CAR, name="robot", pose=Pose.from_xyz_rpy((0, 0, 0), (0, 0, 0.1))))
    for _ in range(50):
        pw.step()
    return pw, car


def test_ray_cast_ground_matches_tinyrenderers_drawing(output_dir: Path) -> None:
    images = []
    for gui_planes in (False, True):
        pw, car = _scene(gui_planes)
        try:
            sensor = next(s for s in car.model.sensors() if s.type == "camera")
            cam = Camera(car, sensor, np.random.default_rng(0), (-0.5, 0.1, -0.9), pw.all_flat_planes)
            assert bool(pw.all_flat_planes()) != gui_planes
            cam._noise = None  # compare the drawing itself
            images.append(cam.render())
        finally:
            pw.close()
    ours, reference = images
    (output_dir / "camera_ray_cast_ground.png").write_bytes(encode_png(ours))
    (output_dir / "camera_tinyrenderer_ground.png").write_bytes(encode_png(reference))
    assert ours.shape == (240, 320, 3)
    diff = np.abs(ours.astype(int) - reference.astype(int)).sum(axis=2)
    assert (diff > 30).mean() < 0.005  # the same picture but for a few edge pixels
    # It is a picture: ground below the horizon, the two (shaded grey) boxes, the low one before the ground.
    boxes = ours.astype(int).sum(axis=2) < 400
    assert boxes.sum() > 5000 and boxes[:, 250:].sum() > 500
    assert np.all(ours[-1, :, 0] == ours[-1, 0, 0])  # the bottom row is ground


@pytest.mark.slow
def test_camera_renders_only_while_someone_subscribes(router: str) -> None:
    from diffctl.bus import open_session
    from diffctl.sim.runner import Simulation

    session = open_session()
    sim = Simulation(load_world(EMPTY_WORLD), rtf=0.0, paused=False, session=session)
    stop = threading.Event()
    thread = threading.Thread(target=sim.run, args=(stop,), daemon=True)
    try:
        sim.spawn(load_model(CAR, name="robot"))
        cam = next(s for s in sim.models["robot"].sensors if isinstance(s, CameraSensor))
        thread.start()
        time.sleep(0.5)
        assert cam.frames == 0 and sim.stepper.sim_time_ns > 1_000_000_000
        got: list[dict] = []
        sub = session.declare_subscriber(gz.key("/camera"), lambda s: got.append(gz.decode(s.payload.to_bytes())[1]))
        deadline = time.monotonic() + 10
        while len(got) < 3 and time.monotonic() < deadline:
            time.sleep(0.05)
        assert len(got) >= 3 and cam.frames >= 3
        img = got[-1]
        assert (img["width"], img["height"], img["pixel_format_type"]) == (320, 240, "RGB_INT8")
        assert isinstance(img["data"], bytes) and len(img["data"]) == 320 * 240 * 3  # raw, not base64
        stamps = [gz.stamp_ns(m["header"]) for m in got]
        assert all(b - a == 100_000_000 for a, b in itertools.pairwise(stamps))  # 10 Hz of sim time
        sub.undeclare()
        time.sleep(0.3)
        frames = cam.frames
        time.sleep(0.5)
        assert cam.frames == frames  # nobody listens: no rendering
    finally:
        stop.set()
        thread.join(5)
        sim.close()
