"""End to end on mock hardware: manager + both spawners as real processes over a real router, driven by
TwistStamped like a teleop node would; odometry, wheel states, timeout braking, stale and NaN commands."""

from __future__ import annotations

import itertools
import math
import re
import subprocess
import threading
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SDF = REPO / "description" / "my_diff_car_control.sdf"
CONFIG = REPO / "config" / "diff_drive_controller.yaml"
CTRL = "/diffbot_base_controller"
WHEEL_RADIUS_M = 0.04


def start_manager(procs, log_path: Path, *extra: str) -> subprocess.Popen:
    return procs.diffctl(
        "control",
        "manager",
        "--description",
        str(SDF),
        "--param-file",
        str(CONFIG),
        "--hardware-plugin",
        "mock_components/GenericSystem",
        "--hardware-param",
        "calculate_dynamics=true",
        *extra,
        "--ros-args",
        "-p",
        "use_sim_time:=false",
        stdout=log_path.open("w"),
        stderr=subprocess.STDOUT,
    )


def spawn(procs, *args: str, timeout_s: float = 20.0) -> tuple[int, str]:
    p = procs.diffctl("spawn", "controller", *args)
    out, _ = p.communicate(timeout=timeout_s)
    return p.returncode, out


BOUND_S = 30.0  # a failure bound, never a guess of how long something takes


class Recorder:
    def __init__(self) -> None:
        self.lock = threading.Condition()
        self.odom: list[tuple[float, float, float]] = []  # (stamp s, x m, vx m/s)
        self.joints: list[tuple[float, float]] = []  # (stamp s, left wheel position rad)

    def on_odom(self, msg) -> None:
        t = msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9
        with self.lock:
            self.odom.append((t, msg.pose.pose.position.x, msg.twist.twist.linear.x))
            self.lock.notify_all()

    def on_joints(self, msg) -> None:
        t = msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9
        if "base_link_to_left_wheel" in msg.name:
            with self.lock:
                self.joints.append((t, float(msg.position[list(msg.name).index("base_link_to_left_wheel")])))
                self.lock.notify_all()

    def wait(self, condition, what: str) -> None:
        """Until `condition()` holds (checked under the lock at each sample), at most BOUND_S."""
        with self.lock:
            assert self.lock.wait_for(condition, BOUND_S), f"{what} (within {BOUND_S} s)"

    def odom_after(self, t: float) -> list[tuple[float, float, float]]:
        with self.lock:
            return [s for s in self.odom if s[0] > t]

    def last_odom(self) -> tuple[float, float, float]:
        with self.lock:
            return self.odom[-1]

    def at(self, series: list, t: float) -> tuple:
        with self.lock:
            return min(series, key=lambda s: abs(s[0] - t))


def publish_for(pub, node, duration_s: float, x: float, *, stamp_offset_s: float = 0.0, rate_hz: float = 50.0,
                until: threading.Event | None = None) -> float:
    """Publish TwistStamped(linear.x=x) at rate_hz for duration_s (or until `until` is set, at most BOUND_S);
    returns the last stamp (s)."""
    from diffctl.interfaces import types

    end = time.monotonic() + (BOUND_S if until is not None else duration_s)
    last = 0.0
    while time.monotonic() < end and not (until is not None and until.is_set()):
        now_ns = time.time_ns() + int(stamp_offset_s * 1e9)
        msg = types.new(
            "geometry_msgs/msg/TwistStamped",
            {"header": {"stamp": {"sec": now_ns // 10**9, "nanosec": now_ns % 10**9}}, "twist": {"linear": {"x": x}}},
        )
        pub.publish(msg)
        last = now_ns / 1e9
        time.sleep(1.0 / rate_hz)
    return last


@pytest.mark.slow
def test_mock_control_drives_brakes_and_rejects_bad_commands(router, procs, tmp_path, output_dir, monkeypatch) -> None:
    from tests.probe import Probe

    monkeypatch.setenv("ROS_HOME", str(tmp_path))
    log_path = output_dir / "manager.log"
    t0 = time.monotonic()
    cm = start_manager(procs, log_path)
    rc, out = spawn(procs, "diffbot_base_controller", "--param-file", str(CONFIG))
    assert rc == 0, out
    rc, out = spawn(procs, "joint_state_broadcaster")
    assert rc == 0, out
    startup_s = time.monotonic() - t0
    assert "Configured and activated joint_state_broadcaster" in out

    node = Probe("test_teleop")
    rec = Recorder()
    node.create_subscription(f"{CTRL}/odom", "nav_msgs/msg/Odometry", rec.on_odom)
    node.create_subscription("/joint_states", "sensor_msgs/msg/JointState", rec.on_joints)
    pub = node.create_publisher(f"{CTRL}/cmd_vel", "geometry_msgs/msg/TwistStamped")
    rec.wait(lambda: rec.odom and rec.joints and pub.subscription_count > 0,
             "no /odom or /joint_states from the controllers, or no subscriber of cmd_vel")
    x_rest = rec.last_odom()[1]

    # A stale command (stamped 2 s ago, older than cmd_vel_timeout 0.5 s) and NaN / inf commands: no motion, in
    # the odometry of the cycles after them.
    publish_for(pub, node, 0.3, 0.5, stamp_offset_s=-2.0)
    publish_for(pub, node, 0.3, math.nan)
    sent = publish_for(pub, node, 0.3, math.inf)
    rec.wait(lambda: len([s for s in rec.odom if s[0] > sent]) >= 5, "no odometry after the bad commands")
    _, x, vx = rec.last_odom()
    assert x == pytest.approx(x_rest, abs=1e-9) and vx == 0.0
    assert "Ignoring the received message" in log_path.read_text()

    # Drive at 0.2 m/s (the limiter, max_acceleration 1 m/s², reaches it within 0.2 s) until the odometry holds
    # 1 s of it, however long the machine takes to get there.
    reached = threading.Event()
    stamps: list[float] = []
    driver = threading.Thread(target=lambda: stamps.append(publish_for(pub, node, 0, 0.2, until=reached)))
    driver.start()
    try:
        def steady_second() -> bool:
            steady = [s for s in rec.odom if abs(s[2] - 0.2) < 1e-9]
            return bool(steady) and steady[-1][0] - steady[0][0] >= 1.0
        rec.wait(steady_second, "odometry never held 0.2 m/s for 1 s")
    finally:
        reached.set()
        driver.join()
    last_stamp = stamps[0]
    with rec.lock:
        steady = [s for s in rec.odom if abs(s[2] - 0.2) < 1e-9]
        t_a, x_a, _ = steady[0]
        t_b, x_b, _ = [s for s in steady if s[0] <= t_a + 1.0][-1]  # whatever the cycles' spacing
    assert t_b - t_a >= 0.9 and t_b < last_stamp
    advance_m = x_b - x_a
    assert advance_m / (t_b - t_a) == pytest.approx(0.2, rel=0.02)  # integrated as the stamps say
    # The same window on the (mock) wheels: 0.2 m/s ÷ 0.04 m = 5 rad/s.
    (ja, qa), (jb, qb) = rec.at(rec.joints, t_a), rec.at(rec.joints, t_b)
    assert (qb - qa) / (jb - ja) == pytest.approx(0.2 / WHEEL_RADIUS_M, rel=0.02)

    # Stopped publishing: the last command holds until cmd_vel_timeout (0.5 s) after its stamp, then the car
    # brakes through the limiter (1 m/s²) and stays put. Judged on the controller's own stamps, so a late cycle
    # on a loaded machine moves nothing.
    rec.wait(lambda: len([s for s in rec.odom if s[0] > last_stamp and s[2] == 0.0]) >= 5, "the car never stopped")
    after = rec.odom_after(last_stamp)
    moving = [s for s in after if s[2] > 0.199]
    assert moving and moving[-1][0] >= last_stamp + 0.5 - 0.051, "braked before cmd_vel_timeout"
    assert all(s[2] < 0.199 for s in after if s[0] > last_stamp + 0.5 + 1e-3), "still driving after cmd_vel_timeout"
    decel = [s for s in after if 0.0 < s[2] < 0.199]
    assert decel, "braking skipped the limiter"
    for (t0, _, v0), (t1, _, v1) in itertools.pairwise(after):
        assert v0 - v1 <= 1.0 * (t1 - t0) + 1e-6, f"braked harder than 1 m/s² between {t0} and {t1}"
    stopped = [s for s in after if s[2] == 0.0]
    assert len({s[1] for s in stopped}) == 1, "moved after stopping"
    assert "Velocity command timed out" in log_path.read_text() or "timed out" in log_path.read_text()
    node.close()

    # Ctrl-C: every controller deactivated and unloaded, the process gone promptly.
    t_stop = time.monotonic()
    rc = procs.stop(cm)
    assert rc == 0 and time.monotonic() - t_stop < 3.0
    print(f"startup to both controllers active: {startup_s:.2f} s; steady 1 s advance {advance_m:.5f} m")


@pytest.mark.slow
def test_launch_mock_control_activates_both_controllers_and_drives(router, procs, tmp_path, monkeypatch) -> None:
    """The same graph through the launch engine: `diffctl launch mock_control`, then Ctrl-C reaps everything."""
    from tests.probe import Probe

    monkeypatch.setenv("ROS_HOME", str(tmp_path))
    log_path = tmp_path / "launch.log"
    launch = procs.diffctl("launch", "mock_control", "--no-color", stdout=log_path.open("w"), stderr=subprocess.STDOUT)
    deadline = time.monotonic() + 30
    while "controllers active on mock hardware" not in log_path.read_text():
        assert launch.poll() is None, log_path.read_text()
        assert time.monotonic() < deadline, log_path.read_text()
        time.sleep(0.1)
    node = Probe("test_launch_teleop")
    rec = Recorder()
    node.create_subscription(f"{CTRL}/odom", "nav_msgs/msg/Odometry", rec.on_odom)
    node.create_subscription("/joint_states", "sensor_msgs/msg/JointState", rec.on_joints)
    pub = node.create_publisher(f"{CTRL}/cmd_vel", "geometry_msgs/msg/TwistStamped")
    while (not rec.odom or pub.subscription_count == 0) and time.monotonic() < deadline:
        time.sleep(0.05)
    x0 = rec.last_odom()[1]
    publish_for(pub, node, 1.0, 0.2)
    assert rec.last_odom()[1] - x0 > 0.1
    assert rec.joints and rec.joints[-1][1] - rec.joints[0][1] > 2.0  # the mock wheels turned
    node.close()
    assert procs.stop(launch, timeout_s=10) == 0, log_path.read_text()
    text = log_path.read_text()
    assert re.search(r"\[spawner_diffbot_base_controller\]: process has finished cleanly \[pid \d+\]", text), text
    assert re.search(r"\[controller_manager\]: process has finished cleanly \[pid \d+\]", text), text  # on SIGINT
