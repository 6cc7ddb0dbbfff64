"""The simulator as a process on a real router: bad input, spawning, world control, its controller manager."""

from __future__ import annotations

import json
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import pytest
from sim_helpers import CAR, CAR_CONTROL, EMPTY_WORLD, REPO

CONTROLLERS = REPO / "config" / "diff_drive_controller.yaml"


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
    r = run_cli("sim", "run", "--seed", "x", str(EMPTY_WORLD))  # (-v9 is gz sim's loudest, as atoi reads it)
    assert r.returncode == 2 and "invalid argument: --seed x" in r.stderr


@pytest.mark.slow
def test_spawn_entity_and_world_control(router: str, procs: Any, tmp_path: Path) -> None:
    from tests.probe import Probe

    sim, session = start_sim(procs, "-v", "3")  # paused
    r = run_cli("spawn", "entity", "--file", str(CAR), "--name", "robot", "--x", "1", "--Y", "1.5707963")
    assert r.returncode == 0, r.stderr
    assert "spawned 'robot'" in r.stdout
    # The ROS form, from a latched /robot_description, and a name already taken: exit 1, the sim runs on.
    node = Probe("description_source")
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
    # ros_gz_sim create's words and exit code; the simulator's reason names the file and the line
    assert r.stderr.startswith(f"error: Entity creation failed: {bad}:"), r.stderr
    malformed = tmp_path / "malformed.sdf"
    malformed.write_text("<sdf version='1.8'>\n<model name='x'>\n<link name='a'>\n</model></sdf>\n")
    r = run_cli("spawn", "entity", "-file", str(malformed), "-name", "broken")
    assert r.returncode == 1 and r.stderr.startswith(f"error: Entity creation failed: {malformed}:4:"), r.stderr
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
    assert running[-1]["step_time_us"] > 0
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


def _controlled_run(procs: Any, session: Any, tmp_path: Path, batches: list[int]) -> tuple[float, ...]:
    """A fresh sim, paused at sim time 0, with the ros2_control car: its in-simulator manager answers at once;
    the spawner's switch waits for the manager's first cycle, which one step runs; then a command is given and
    the world stepped in `batches`. The car's pose after them."""
    from tests.probe import Probe

    desc = tmp_path / "car.sdf"
    desc.write_text(CAR_CONTROL.read_text().replace("PARAMETERS_CONFIG_FILE_PLACEHOLDER", str(CONTROLLERS)))
    # The manager's debug messages say when the spawner's switch request waits for a control cycle.
    sim, _ = start_sim(procs, "--rtf", "0", "--ros-args", "--log-level", "controller_manager:=debug", "--")  # paused
    lines: list[str] = []
    threading.Thread(target=lambda: lines.extend(iter(sim.stdout.readline, "")), daemon=True).start()
    node = Probe("driver")
    try:
        assert run_cli("spawn", "entity", "--file", str(desc), "--name", "robot").returncode == 0
        # The manager answers while the world is paused: a spawner only waits for its services.
        r = run_cli("control", "list_hardware_components")
        assert r.returncode == 0 and "gz_ros2_control/GazeboSimSystem" in r.stdout, r.stdout + r.stderr
        spawner = procs.diffctl(
            "spawn",
            "controller",
            "diffbot_base_controller",
            "joint_state_broadcaster",
            "--param-file",
            str(CONTROLLERS),
            "--activate-as-group",
            cwd=REPO,
        )
        lister = node.create_client(
            "/controller_manager/list_controllers", "controller_manager_msgs/srv/ListControllers"
        )

        def configured() -> bool:
            states = [c.state for c in lister.call({}, timeout=10.0).controller]
            return states == ["inactive", "inactive"]

        wait_for(configured, what="both controllers configured")
        wait_for(lambda: any("Requested atomic controller switch" in line for line in lines),
                 what="the spawner's switch request waiting for a control cycle")
        assert query(session, "gz/world/empty/control", {"multi_step": 1})["sim_time_ns"] == 1_000_000
        assert spawner.wait(30) == 0, spawner.stdout.read() + "".join(lines)
        pub = node.create_publisher("/diffbot_base_controller/cmd_vel", "geometry_msgs/msg/TwistStamped")
        wait_for(lambda: pub.subscription_count > 0, what="the controller's subscription")
        pub.publish({"twist": {"linear": {"x": 0.4}, "angular": {"z": 0.5}}})
        time.sleep(0.5)  # delivered while paused: it is the newest command when the world steps
        for n in batches:
            assert query(session, "gz/world/empty/control", {"multi_step": n}, timeout=60)["ok"]
            time.sleep(0.3)  # wall time between batches must not matter
        robot = next(m for m in query(session, "gz/world/empty/state")["models"] if m["name"] == "robot")["pose"]
        return robot["x"], robot["y"], robot["yaw"]
    finally:
        node.close()
        procs.stop(sim)


@pytest.mark.slow
def test_the_simulator_hosts_the_manager_and_results_do_not_depend_on_timing(
    router: str, procs: Any, tmp_path: Path
) -> None:
    from diffctl.bus import open_session

    session = open_session()
    a = _controlled_run(procs, session, tmp_path, [400])
    b = _controlled_run(procs, session, tmp_path, [100, 100, 200])
    assert a == b  # the same to the last bit: the manager is stepped on sim time, inside the physics loop
    # It drove: 0.4 s of sim time ramping at 1 m/s² and 1 rad/s² (the tutorial's limits) towards 0.4 m/s, 0.5 rad/s.
    assert a[0] > 0.05 and a[2] > 0.05
