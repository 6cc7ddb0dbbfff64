"""`sim run --gui` opens PyBullet's window (Gazebo's GUI counterpart): a real window under Xvfb, screenshotted."""

from __future__ import annotations

import shutil
import struct
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from sim_helpers import CAR, EMPTY_WORLD, REPO
from test_sim_process import query, run_cli, wait_for

from diffctl.viz.png import encode_png


def xwd_to_rgb(raw: bytes) -> np.ndarray:
    """The pixels of an XWD dump (what Xvfb -fbdir keeps of its screen), as (h, w, 3) RGB."""
    hdr = struct.unpack(">25I", raw[:100])
    header_size, _version, _fmt, _depth, width, height = hdr[:6]
    byte_order, bits_per_pixel, bytes_per_line, ncolors = hdr[7], hdr[11], hdr[12], hdr[19]
    assert bits_per_pixel == 32, f"unexpected XWD pixel size {bits_per_pixel}"
    offset = header_size + ncolors * 12
    px = np.frombuffer(raw, np.uint8, count=height * bytes_per_line, offset=offset)
    px = px.reshape(height, bytes_per_line)[:, : width * 4].reshape(height, width, 4)
    return np.ascontiguousarray(px[:, :, [2, 1, 0]] if byte_order == 0 else px[:, :, [1, 2, 3]])


@pytest.mark.slow
def test_gui_window_shows_the_car(router: str, procs: Any, tmp_path: Path, output_dir: Path) -> None:
    xvfb = shutil.which("Xvfb")
    if xvfb is None:
        pytest.fail("Xvfb is missing: install Debian's xvfb (`make system-deps` or `apt-get install xvfb`)")
    fbdir = tmp_path / "fb"
    fbdir.mkdir()
    # Its diagnostics to a file of their own: Xvfb that meets another starting at the same moment says
    # "server already running" on stderr, tries the next display, and only its number belongs on stdout.
    xvfb_log = tmp_path / "xvfb.log"
    server = procs.start(
        [xvfb, "-displayfd", "1", "-screen", "0", "1024x768x24", "-fbdir", str(fbdir), "-nolisten", "tcp"],
        stderr=xvfb_log.open("w"),
    )
    display = server.stdout.readline().strip()
    assert display.isdigit(), f"Xvfb did not report its display: {display!r}; it said: {xvfb_log.read_text()!r}"
    import os

    env = {**os.environ, "DISPLAY": f":{display}"}
    sim = procs.diffctl("sim", "run", "--gui", "-r", str(EMPTY_WORLD), cwd=REPO, env=env)
    from diffctl.bus import open_session

    session = open_session()
    wait_for(
        lambda: list(session.liveliness().get("gz/world/empty/sim", timeout=0.5)) or sim.poll() is not None,
        what="the sim",
    )
    assert sim.poll() is None, sim.stdout.read()
    r = run_cli("spawn", "entity", "--file", str(CAR), "--name", "robot")
    assert r.returncode == 0, r.stderr
    assert any(m["name"] == "robot" for m in query(session, "gz/world/empty/state")["models"])
    # The window is software-rendered: poll the screen until the car shows (or a generous deadline passes).
    deadline = time.monotonic() + 20
    while True:
        rgb = xwd_to_rgb((fbdir / "Xvfb_screen0").read_bytes())
        r_, g_, b_ = (rgb[:, :, i].astype(int) for i in range(3))
        blue = (b_ > 150) & (r_ < 90) & (g_ < 130)  # the chassis (diffuse 0.1 0.3 0.8)
        red = (r_ > 150) & (g_ < 60) & (b_ < 60)  # the lidar puck (0.9 0.1 0.1)
        grey = (abs(r_ - g_) < 8) & (abs(g_ - b_) < 8) & (r_ > 120)  # the ground
        if (blue.sum() > 1000 and red.sum() > 50) or time.monotonic() > deadline:
            break
        time.sleep(0.25)
    shot = output_dir / "sim_gui.png"
    shot.write_bytes(encode_png(rgb))
    assert blue.sum() > 1000, f"the car is not visible in {shot}"
    assert red.sum() > 50, f"the lidar puck is not visible in {shot}"
    assert grey.mean() > 0.3, f"the ground is not visible in {shot}"
    ys, xs = np.nonzero(blue)
    assert 200 < xs.mean() < 824 and 150 < ys.mean() < 618  # the camera looks at the car
    assert procs.stop(sim) == 0
