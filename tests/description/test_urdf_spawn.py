"""`create -file` and `create -string` take a URDF as they take SDF: a real simulator on a real router."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from diffctl.bus import gz
from tests.waiting import wait_for

REPO = Path(__file__).resolve().parents[2]
EMPTY = REPO / "diffctl" / "workspace" / "component_shares" / "ros_gz_sim" / "worlds" / "empty.sdf"
CAR = (Path(__file__).resolve().parent / "data" / "urdf" / "diff_car.urdf").read_text()
# Without the gz_ros2_control plugin: this test is about the model, not the manager it would host.
CAR_MODEL = re.sub(r"<gazebo>\s*<plugin.*?</gazebo>", "", CAR, flags=re.S)


def _cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "diffctl", *args], capture_output=True, text=True, timeout=120, cwd=REPO
    )


def _query(session: Any, key: str, body: dict[str, Any] | None = None) -> dict[str, Any]:
    for reply in session.get(key, payload=json.dumps(body or {}).encode(), timeout=20.0):
        if reply.ok is not None:
            return json.loads(reply.ok.payload.to_bytes())
    raise AssertionError(f"no reply on {key}")


def test_urdf_by_file_and_by_string(router: str, procs: Any, tmp_path: Path) -> None:
    from diffctl.bus import open_session

    sim = procs.diffctl("sim", "run", "-v", "3", str(EMPTY), cwd=REPO)  # paused
    session = open_session()
    assert wait_for(
        lambda: bool(list(session.liveliness().get("gz/world/empty/sim", timeout=0.5))) or sim.poll() is not None,
        60,
    )
    assert sim.poll() is None

    urdf = tmp_path / "diff_car.urdf"
    urdf.write_text(CAR_MODEL)
    run = _cli("spawn", "entity", "-file", str(urdf), "-name", "by_file")
    assert run.returncode == 0, run.stderr
    run = _cli("spawn", "entity", "-string", CAR_MODEL, "-name", "by_string", "-y", "1")
    assert run.returncode == 0, run.stderr
    broken = tmp_path / "broken.urdf"
    broken.write_text(
        CAR_MODEL.replace(
            '<sphere radius="0.02"/></geometry></collision>',
            '<mesh filename="package://diffctl_nothing/c.stl"/></geometry></collision>',
        )
    )
    # as Gazebo: a collision mesh it cannot find is left out with an error from the simulator; the entity spawns
    run = _cli("spawn", "entity", "-file", str(broken), "-name", "broken", "-y", "-1")
    assert run.returncode == 0, run.stderr

    poses: list[dict[str, Any]] = []
    session.declare_subscriber(gz.key("/model/by_file/pose"), lambda s: poses.append(gz.decode(s.payload.to_bytes())))
    assert _query(session, "gz/world/empty/control", {"multi_step": 1000})["ok"]
    state = _query(session, "gz/world/empty/state")
    assert [m["name"] for m in state["models"]] == ["ground_plane", "by_file", "by_string", "broken"]
    assert state["sim_time_ns"] == 1_000_000_000
    by_file = next(m for m in state["models"] if m["name"] == "by_file")["pose"]
    # wheels and the lumped caster hold the car on the ground, level, where it was put
    assert by_file["z"] == pytest.approx(0.0, abs=0.01)
    assert by_file["roll"] == pytest.approx(0.0, abs=0.02) and by_file["pitch"] == pytest.approx(0.0, abs=0.02)
    assert (by_file["x"], by_file["y"]) == pytest.approx((0.0, 0.0), abs=0.01)
    assert sim.poll() is None
    procs.stop(sim)
    log = sim.stdout.read()
    assert f"{broken}:" in log and "mesh 'package://diffctl_nothing/c.stl' not found" in log, log
    assert "the model loads without this collision" in log
