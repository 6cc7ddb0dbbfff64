"""The simulator as a process on a real router: bad input, spawning, world control, the ros2_control lockstep."""

from __future__ import annotations

import itertools
import json
import queue
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest
from sim_helpers import CAR, CAR_CONTROL, EMPTY_WORLD, REPO

from diffctl.bus import hw_endpoint as hw


def run_cli(*args: str, timeout: float = 60) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "diffctl", *args], capture_output=True, text=True, timeout=timeout, cwd=REPO
    )


def query(session: Any, key: str, body: dict[str, Any] | None = None, timeout: float = 10.0) -> dict[str, Any]:
    for r in session.get(key, payload=json.dumps(body or {}).encode(), timeout=timeout):
        if r.ok is not None:
            return json.loads(r.ok.payload.to_bytes())
    raise AssertionError(f"no reply on {key}")


def wait_for(pred: Any, timeout: float = 20.0, what: str = "condition") -> Any:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        v = pred()
        if v:
            return v
        time.sleep(0.05)
    raise AssertionError(f"timed out waiting for {what}")


def start_sim(procs: Any, *args: str) -> Any:
    from diffctl.bus import open_session

    p = procs.diffctl("sim", "run", *args, str(EMPTY_WORLD), cwd=REPO)
    session = open_session()
    wait_for(
        lambda: list(session.liveliness().get("gz/world/empty/sim", timeout=0.5)) or p.poll() is not None,
        what="the sim's token",
    )
    assert p.poll() is None, p.stdout.read()
    return p, session


def test_bad_input_exits_2_with_one_line(tmp_path: Path) -> None:
    r = run_cli("sim", "run", "-r", str(tmp_path / "nope.world"))
    assert r.returncode == 2 and "world file" in r.stderr and "not found" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    bad = tmp_path / "bad.world"
    bad.write_text(
        '<sdf version="1.8"><world name="w"><model name="m"><link name="l"><pose>1 2</pose></link>'
        "</model></world></sdf>"
    )
    r = run_cli("sim", "run", "-r", str(bad))
    assert r.returncode == 2 and "bad.world:1" in r.stderr and "pose" in r.stderr
    assert "Traceback" not in r.stderr
    r = run_cli("sim", "run", "-v9", str(EMPTY_WORLD))
    assert r.returncode == 2 and "verbosity" in r.stderr


@pytest.mark.slow
def test_spawn_entity_and_world_control(router: str, procs: Any, tmp_path: Path) -> None:
    from diffctl.bus import Node

    sim, session = start_sim(procs, "-v", "3")  # paused
    r = run_cli("spawn", "entity", "--file", str(CAR), "--name", "robot", "--x", "1", "--Y", "1.5707963")
    assert r.returncode == 0, r.stderr
    assert "spawned 'robot'" in r.stdout
    # The ROS form, from a latched /robot_description, and a name already taken: exit 1, the sim runs on.
    node = Node("description_source")
    pub = node.create_publisher("/robot_description", "std_msgs/msg/String", latched=True)
    pub.publish({"data": CAR.read_text()})
    r = run_cli("spawn", "entity", "-topic", "/robot_description", "-name", "robot", "--timeout", "10")
    assert r.returncode == 1 and "already exists" in r.stderr, r.stderr
    r = run_cli("spawn", "entity", "-topic", "/robot_description", "-name", "robot2", "-y", "2")
    assert r.returncode == 0, r.stderr
    bad = tmp_path / "bad.sdf"
    bad.write_text(CAR.read_text().replace('type="continuous"', 'type="screw"', 1))
    r = run_cli("spawn", "entity", "--file", str(bad), "--name", "broken")
    assert r.returncode == 1 and "screw" in r.stderr and len(r.stderr.strip().splitlines()) == 1
    assert sim.poll() is None

    st = query(session, "gz/world/empty/state")
    assert st["paused"] and st["sim_time_ns"] == 0
    robot = next(m for m in st["models"] if m["name"] == "robot")
    assert (robot["pose"]["x"], robot["pose"]["yaw"]) == pytest.approx((1.0, 1.5707963), abs=1e-6)
    assert [m["name"] for m in st["models"]] == ["ground_plane", "robot", "robot2"]

    # Step 250 while paused: the answer comes when they are done.
    st = query(session, "gz/world/empty/control", {"multi_step": 250})
    assert st["ok"] and st["paused"] and st["sim_time_ns"] == 250_000_000 and st["iterations"] == 250
    time.sleep(0.3)
    assert query(session, "gz/world/empty/state")["sim_time_ns"] == 250_000_000  # still paused
    stats: list[dict] = []
    from diffctl.bus import gz

    topics: dict[str, list] = {"/lidar": [], "/imu": [], "/model/robot/pose": [], "/clock": []}
    flood = [
        session.declare_subscriber(gz.key(t), lambda s, box=box: box.append(gz.decode(s.payload.to_bytes())))
        for t, box in topics.items()
    ]

    session.declare_subscriber(gz.key("/world/empty/stats"), lambda s: stats.append(gz.decode(s.payload.to_bytes())[1]))
    wait_for(lambda: stats, what="stats while paused")
    assert stats[-1]["paused"] is True and stats[-1]["iterations"] == 250
    assert query(session, "gz/world/empty/control", {"pause": False, "rtf": 0})["ok"]
    wait_for(lambda: query(session, "gz/world/empty/state")["sim_time_ns"] > 2_000_000_000, what="sim time")
    wait_for(lambda: all(topics.values()), what="sensor, pose and clock topics")
    assert {t: v[-1][0] for t, v in topics.items()} == {
        "/lidar": "gz.msgs.LaserScan",
        "/imu": "gz.msgs.IMU",
        "/model/robot/pose": "gz.msgs.Pose_V",
        "/clock": "gz.msgs.Clock",
    }
    assert topics["/imu"][-1][1]["linear_acceleration"]["z"] == pytest.approx(9.8, abs=0.2)
    assert topics["/lidar"][-1][1]["count"] == 360 and topics["/lidar"][-1][1]["frame"] == "lidar_link"
    pose = topics["/model/robot/pose"][-1][1]["pose"][0]
    assert pose["name"] == "robot" and pose["position"]["x"] == pytest.approx(1.0, abs=0.01)
    # At rtf 0 these topics arrive thousands of times a second; decoding them in this process would starve
    # the 5 Hz stats subscription on a fast machine.
    for sub in flood:
        sub.undeclare()
    running = wait_for(lambda: [m for m in stats if not m["paused"] and m["real_time_factor"] > 1], what="stats")
    assert running[-1]["step_time_us"] > 0 and running[-1]["lockstep_overruns"] == 0
    assert running[-1]["step_size"] == {"sec": 0, "nsec": 1_000_000} and running[-1]["model_count"] == 3
    st = query(session, "gz/world/empty/control", {"reset": {"all": True}, "pause": True})
    assert st["paused"] and st["sim_time_ns"] == 0
    assert query(session, "gz/world/empty/control", {"multi_step": -3})["ok"] is False
    assert query(session, "gz/world/empty/control", {"rtf": "fast"})["ok"] is False

    # The same from the command line.
    r = run_cli("sim", "step", "40")
    assert r.returncode == 0 and "paused at sim time 0.040 s (40 steps)" in r.stdout, r.stdout + r.stderr
    r = run_cli("sim", "state")
    assert r.returncode == 0 and "robot2" in r.stdout and "world 'empty'" in r.stdout, r.stderr
    assert run_cli("sim", "resume").stdout.startswith("running")
    assert run_cli("sim", "pause").stdout.startswith("paused")
    r = run_cli("sim", "step", "1", "--world", "mars")
    assert r.returncode == 1 and "no simulator runs world 'mars'" in r.stderr
    r = run_cli("spawn", "entity", "--remove", "robot2")
    assert r.returncode == 0, r.stderr
    assert [m["name"] for m in query(session, "gz/world/empty/state")["models"]] == ["ground_plane", "robot"]
    assert procs.stop(sim) == 0


@pytest.mark.slow
def test_lockstep_with_a_fake_controller_manager(router: str, procs: Any) -> None:
    import zenoh

    sim, session = start_sim(procs, "-r", "--rtf", "0")
    r = run_cli("spawn", "entity", "--file", str(CAR_CONTROL), "--name", "robot")
    assert r.returncode == 0, r.stderr
    assert wait_for(lambda: hw.endpoint_models(session)) == ["robot"]
    info = query(session, hw.info_key("robot"))
    assert [j["name"] for j in info["joints"]] == ["base_link_to_right_wheel", "base_link_to_left_wheel"]
    assert info["joints"][0]["command_interfaces"] == ["velocity"]
    assert info["physics_step_s"] == pytest.approx(0.001)

    states: queue.Queue = queue.Queue()
    session.declare_subscriber(hw.state_key("robot"), lambda s: states.put(hw.decode_state(s.payload.to_bytes())))
    token = session.liveliness().declare_token(hw.manager_key("robot"))
    cmd_pub = session.declare_publisher(hw.command_key("robot"))
    reply = query(session, hw.attach_key("robot"), {"update_rate": 20, "manager": "fake"})
    assert reply["ok"] and reply["control_period_ns"] == 50_000_000
    # A second manager is refused while this one is attached.
    assert not query(session, hw.attach_key("robot"), {"update_rate": 20, "manager": "other"})["ok"]

    first = states.get(timeout=10)
    assert first.tick == reply["next_tick"]
    seen = [first]
    wheel = 0.2 / 0.04  # 0.2 m/s
    for _ in range(40):
        s = seen[-1]
        if len(seen) == 5:
            # Hold the answer back: the sim must wait for it, however fast it could run.
            time.sleep(0.3)
            assert states.empty()
        cmd_pub.put(hw.encode_command(s.tick, [wheel, wheel], None, None))
        seen.append(states.get(timeout=10))
    ticks = [s.tick for s in seen]
    assert ticks == list(range(ticks[0], ticks[0] + len(ticks)))
    periods = {b.sim_time_ns - a.sim_time_ns for a, b in itertools.pairwise(seen)}
    assert periods == {50_000_000}
    # 40 periods = 2 s at 0.2 m/s: the wheels turned and report it.
    assert seen[-1].velocity.tolist() == pytest.approx([wheel, wheel], rel=0.02)
    assert seen[-1].position[0] - seen[0].position[0] == pytest.approx(wheel * 2.0, rel=0.05)

    # A missed deadline is counted, then the sim goes on with the joints held.
    before = query(session, hw.info_key("robot"))["lockstep_overruns"]  # 0 unless this machine stalled 1 s
    last = seen[-1]
    nxt = states.get(timeout=10)  # published after the 1 s deadline for `last` expired
    assert nxt.tick == last.tick + 1
    assert query(session, hw.info_key("robot"))["lockstep_overruns"] == before + 1
    assert abs(nxt.velocity).max() < 0.2  # held (velocity 0), after the deadline

    # The manager disappears: the sim detaches and runs on, joints held.
    token.undeclare()
    t0 = query(session, "gz/world/empty/state")["sim_time_ns"]
    wait_for(lambda: query(session, "gz/world/empty/state")["sim_time_ns"] > t0 + 3_000_000_000, what="run on")
    info = query(session, hw.info_key("robot"))
    assert info["manager"] is None
    pose0 = next(m for m in query(session, "gz/world/empty/state")["models"] if m["name"] == "robot")["pose"]
    time.sleep(0.3)
    pose1 = next(m for m in query(session, "gz/world/empty/state")["models"] if m["name"] == "robot")["pose"]
    assert abs(pose1["x"] - pose0["x"]) < 5e-3  # held: at most contact-solver creep over ~10 s of sim time
    assert pose0["x"] > 0.35  # it did drive ~0.4 m while commanded
    del zenoh
    assert procs.stop(sim) == 0


def _lockstep_run(procs: Any, session: Any) -> list[hw.State]:
    """A sim started paused, the ros2_control car spawned and attached at sim time 0, then driven in lockstep
    through a fixed command schedule while the sim runs as fast as it can."""
    sim = procs.diffctl("sim", "run", "--rtf", "0", str(EMPTY_WORLD), cwd=REPO)
    try:
        wait_for(lambda: list(session.liveliness().get("gz/world/empty/sim", timeout=0.5)), what="the sim")
        assert run_cli("spawn", "entity", "--file", str(CAR_CONTROL), "--name", "robot").returncode == 0
        wait_for(lambda: hw.endpoint_models(session), what="the endpoint")
        states: queue.Queue = queue.Queue()
        sub = session.declare_subscriber(
            hw.state_key("robot"), lambda s: states.put(hw.decode_state(s.payload.to_bytes()))
        )
        token = session.liveliness().declare_token(hw.manager_key("robot"))
        pub = session.declare_publisher(hw.command_key("robot"))
        assert query(session, hw.attach_key("robot"), {"update_rate": 50, "manager": "det"})["ok"]
        assert query(session, "gz/world/empty/control", {"pause": False})["ok"]
        out = []
        for k in range(60):
            s = states.get(timeout=10)
            out.append(s)
            left, right = (4.0, 6.0) if k < 30 else (-3.0, 5.0)
            pub.put(hw.encode_command(s.tick, [right, left], None, None))
            if k == 20:
                time.sleep(0.2)  # a slow manager for once: lockstep makes it irrelevant
        token.undeclare()
        sub.undeclare()
        pub.undeclare()
        return out
    finally:
        procs.stop(sim)


@pytest.mark.slow
def test_lockstep_runs_are_bit_identical_whatever_the_timing(router: str, procs: Any) -> None:
    from diffctl.bus import open_session

    session = open_session()
    a = _lockstep_run(procs, session)
    b = _lockstep_run(procs, session)
    assert a[0].sim_time_ns == 1_000_000 and [s.sim_time_ns for s in a] == [s.sim_time_ns for s in b]
    assert a[-1].velocity.tolist() == pytest.approx([5.0, -3.0], rel=0.02)
    for x, y in zip(a, b, strict=True):
        assert (x.tick, x.position.tobytes(), x.velocity.tobytes()) == (
            y.tick,
            y.position.tobytes(),
            y.velocity.tobytes(),
        )
