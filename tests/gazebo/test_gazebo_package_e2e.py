"""A community-shaped Gazebo package brought up from its workspace root with `diffctl launch PKG FILE`: the
environment hook makes model:// resolve, Fuel's ground plane and sun load offline, the robot's COLLADA mesh
and merged sensor kit load, `gz sim` starts through ExecuteProcess, rqt_graph is skipped with a warning."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.gazebo.gazebo_workspace import PKG, build


def _gz(*args: str) -> subprocess.CompletedProcess:
    gz_cli = [sys.executable, "-c", "from diffctl.gz.cli import main; main()"]
    return subprocess.run([*gz_cli, *args], capture_output=True, text=True, timeout=30, env=os.environ.copy())


def _clock_s() -> float | None:
    out = _gz("topic", "-e", "-t", "/clock", "-n", "1", "-d", "5").stdout
    sim = re.search(r"sim \{\n(?:\s+sec: (\d+)\n)?(?:\s+nsec: (\d+)\n)?", out)
    if sim is None:
        return None
    return int(sim.group(1) or 0) + int(sim.group(2) or 0) * 1e-9


@pytest.mark.slow
def test_a_gazebo_package_runs_from_its_workspace_root(stack_env: str, procs, tmp_path: Path, monkeypatch) -> None:
    ws = build(tmp_path)
    for var in ("GZ_SIM_RESOURCE_PATH", "SDF_PATH", "AMENT_PREFIX_PATH", "COLCON_PREFIX_PATH", "DIFFCTL_WORKSPACE"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    monkeypatch.setenv("GZ_FUEL_CACHE_PATH", str(tmp_path / "empty-fuel-cache"))
    monkeypatch.setenv("DIFFCTL_FUEL_OFFLINE", "1")  # nothing may come from the network
    monkeypatch.setenv("ROS_LOG_DIR", str(tmp_path / "log"))
    (tmp_path / "empty-fuel-cache").mkdir()
    launch = procs.diffctl("launch", PKG, "sim.launch.py", cwd=ws)
    try:
        deadline = time.monotonic() + 60
        listing = ""
        while "wedge_bot" not in listing:
            assert launch.poll() is None, launch.stdout.read()
            assert time.monotonic() < deadline, "the world never came up"
            listing = _gz("model", "--list").stdout
            time.sleep(0.3)
        assert listing.endswith("Available models:\n    - ground_plane\n    - wedge_bot\n")
        t0 = _clock_s()
        time.sleep(1.0)
        t1 = _clock_s()
        assert t0 is not None and t1 is not None and t1 > t0, (t0, t1)  # -r: /clock advances
        # the wedge (COLLADA, 0.4 x 0.2 x 0.1 m after <unit> and <scale>) fell from z 0.3 onto Fuel's ground plane
        pose = _gz("model", "-m", "wedge_bot").stdout
        x, y, z = (float(v) for v in re.search(r"\[(\S+) (\S+) (\S+)\]", pose).groups())
        assert abs(x - 1) < 0.05 and abs(y + 2) < 0.05 and -0.01 < z < 0.05, pose
    finally:
        procs.stop(launch)
    out = launch.stdout.read()
    assert "rqt_graph/rqt_graph is a GUI-only tool" in out and out.count("GUI-only tool") == 1
    assert "error" not in out.lower().replace("stderr", ""), out


@pytest.mark.slow
def test_gz_sim_typed_in_the_workspace_applies_its_hooks(router: str, tmp_path: Path, monkeypatch) -> None:
    """No `source install/setup.bash` with diffctl: `gz sim NAME` in a workspace finds the package's world
    and models through the package's hook, runs its iterations and exits 0."""
    ws = build(tmp_path)
    for var in ("GZ_SIM_RESOURCE_PATH", "SDF_PATH", "DIFFCTL_WORKSPACE"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    monkeypatch.setenv("GZ_FUEL_CACHE_PATH", str(tmp_path))
    monkeypatch.setenv("DIFFCTL_FUEL_OFFLINE", "1")
    gz_cli = [sys.executable, "-c", "from diffctl.gz.cli import main; main()"]
    done = subprocess.run(
        [*gz_cli, "sim", "-r", "-s", "--iterations", "50", "-v", "3", "wedge_world.sdf"],
        cwd=ws / "src",
        capture_output=True,
        text=True,
        timeout=60,
        env=os.environ.copy(),
    )
    assert done.returncode == 0, done.stdout + done.stderr
    assert "world 'wedge_world'" in done.stdout + done.stderr
    outside = subprocess.run(
        [*gz_cli, "sim", "-r", "-s", "--iterations", "50", "wedge_world.sdf"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=60,
        env=os.environ.copy(),
    )
    assert outside.returncode == 2 and "not found" in outside.stderr  # outside the workspace: no hook, no world
