"""Faults injected into a running `diffctl launch sim_control` (rtf:=0 unless said): each process SIGKILLed
mid-drive, the launcher SIGKILLed, a controller raising in update(), a flooding publisher and a slow subscriber.

The documented outcomes (launch/sim_control.yaml):
- gz_sim (which hosts the controller manager, as gz_ros2_control does) is `on_exit: shutdown`: everything
  stops cleanly, the launcher names the process and how it ended, and exits 1;
- robot_state_publisher, parameter_bridge and rviz2 (the visualizer) are `respawn: true` (1 s delay): each
  comes back and its output flows again, while the car keeps driving;
- the car never drives on a stale command: a teleop that dies → the controller brakes after cmd_vel_timeout;
- the launcher SIGKILLed: every child exits within 2 s (PR_SET_PDEATHSIG).
"""

from __future__ import annotations

import itertools
import json
import math
import os
import re
import signal
import subprocess
import sys
import time
import urllib.request
from collections.abc import Callable
from pathlib import Path

import pytest

from tests.conftest import REPO, Procs, free_port
from tests.e2e.stack import Stack
from tests.reliability.stack_faults import (
    CMD,
    CONTROLLERS,
    ODOM,
    SEC,
    TWIST_STAMPED,
    alive,
    drive,
    launch_log,
    pids,
    start_stack,
    truth_at,
    wait_until,
)

pytestmark = pytest.mark.slow


def assert_shut_down_cleanly(stack: Stack, name: str, timeout_s: float = 15.0) -> str:
    """The launch ends by itself with exit code 1, naming `name` and its SIGKILL, leaving nothing running."""
    try:
        code = stack.proc.wait(timeout_s)
    except subprocess.TimeoutExpired:
        raise AssertionError(f"the launch did not shut down after {name} was killed:\n{stack.output()}") from None
    log = launch_log(stack)
    assert code == 1, log[-3000:]
    assert re.search(rf"\[{name}\]: process has died \[pid \d+, exit code -9,", log), log[-3000:]
    assert f"process[{name}] was required: shutting down launched system" in log, log[-3000:]
    assert f"launch failed: required process '{name}' was killed by SIGKILL" in log, log[-3000:]
    wait_until(lambda: not stack.survivors(), 2.0, f"every process gone after {name} died: {stack.survivors()}")
    return log


# ------------------------------------------------------------------------------------------------ respawns


def test_relays_respawn_mid_drive_and_a_dead_teleop_brakes_the_car(stack_env: str, tmp_path: Path) -> None:
    viz_port = free_port()
    # rtf:=1: cmd_vel_timeout (0.5 s) is then half a second of wall time too, so a hiccup of this busy test
    # process while a relay restarts cannot starve the controller of commands (at rtf:=0 it is ~20 ms).
    stack = start_stack(tmp_path, "viz:=true", f"viz_port:={viz_port}", rtf="1")
    procs = Procs()
    try:
        wait_until(lambda: "rviz2" in pids(stack), 30, "the visualizer started", stack)
        w = stack.watch
        drive(stack, 0.0, 0.5, 4, 0.5)

        def flows(topic: str, gid_before: set[bytes]) -> bool:
            with w.lock:
                return any(g not in gid_before for _, _, g in w.stamps.get(topic, [])[-20:])

        def gids(topic: str) -> set[bytes]:
            with w.lock:
                return {g for _, _, g in w.stamps.get(topic, [])}

        def page() -> bool:
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{viz_port}/", timeout=1) as r:
                    return r.status == 200
            except OSError:
                return False

        checks: dict[str, Callable[[set[bytes]], bool]] = {
            "robot_state_publisher": lambda before: flows("/tf", before),  # /tf from /joint_states again
            "parameter_bridge": lambda before: flows("/clock", before),  # bridged /clock again
            "rviz2": lambda before: page(),  # the web page answers again
        }
        topic_of = {"robot_state_publisher": "/tf", "parameter_bridge": "/clock", "rviz2": "/clock"}
        wait_until(page, 20, "the visualizer's page answers", stack)
        for name, check in checks.items():
            old = pids(stack)[name]
            before = gids(topic_of[name])
            os.kill(old, signal.SIGKILL)
            wait_until(lambda n=name, o=old: pids(stack)[n] != o, 20, f"{name} respawned", stack)
            log = launch_log(stack)
            assert f"[{name}]: process has died [pid {old}, exit code -9," in log  # then respawned: a new pid
            wait_until(lambda c=check, b=before: c(b), 30, f"{name} working again after its respawn", stack)
            assert not alive(old)
            # The car drove on the whole time: the controller and the sim never depended on the relay.
            assert w.last(w.odom).value[4] == pytest.approx(0.5, abs=0.01), f"after {name}'s respawn"
        stack.descendants()

        # A teleop process on sim time drives the car; SIGKILLed, its last command goes stale and the
        # controller brakes after cmd_vel_timeout (0.5 s) plus its deceleration ramp (1 rad/s²).
        stack.command(CMD, TWIST_STAMPED, None)
        teleop = procs.start([sys.executable, "-m", "tests.reliability.bus_clients", "teleop", "0", "0.8"], cwd=REPO)
        wait_until(lambda: w.last(w.odom).value[4] > 0.79, 30, "the teleop process drives the car", stack)
        os.kill(teleop.pid, signal.SIGKILL)
        # The sim's clock just after the kill: the teleop's last command arrived before it.
        stop_ns = sim_time_ns(stack)
        teleop.wait(5)
        stack.wait_sim(stop_ns + 2 * SEC)
        wait_until(lambda: w.last(w.truth).t_ns >= stop_ns + 2 * SEC, 10, "ground truth past the stop", stack)
        stopped = w.at(w.odom, stop_ns + int(1.6 * SEC)).value[4]
        assert abs(stopped) < 0.02, f"still turning at {stopped:.3f} rad/s 1.6 s after the teleop died"
        ga, gb = truth_at(stack, stop_ns + int(1.6 * SEC)), truth_at(stack, stop_ns + int(2.0 * SEC))
        assert abs(math.remainder(gb[2] - ga[2], math.tau)) < 0.01, "ground truth still turning"

        code = stack.stop(signal.SIGINT)
        assert code == 0, stack.output()
        assert not stack.survivors(), stack.survivors()
    finally:
        procs.close()
        stack.kill()


# ------------------------------------------------------------------------------------------------ required processes


def test_simulator_killed_mid_drive_shuts_everything_down(stack_env: str, tmp_path: Path) -> None:
    stack = start_stack(tmp_path)
    try:
        drive(stack, 0.5, 0.0, 3, 0.5)
        os.kill(pids(stack)["gz_sim"], signal.SIGKILL)
        t0 = time.monotonic()
        assert_shut_down_cleanly(stack, "gz_sim")
        assert time.monotonic() - t0 < 10
    finally:
        stack.kill()


def sim_time_ns(stack: Stack) -> int:
    replies = list(stack.node.session.get("gz/world/empty/state", payload=b"{}", timeout=5.0))
    return next(json.loads(r.ok.payload.to_bytes())["sim_time_ns"] for r in replies if r.ok is not None)


def test_launcher_killed_every_child_exits_within_2s(stack_env: str, tmp_path: Path) -> None:
    stack = start_stack(tmp_path)
    try:
        drive(stack, 0.3, 0.2, 3, 0.3)
        kids = stack.descendants()
        assert len(kids) >= 4, [k.name() for k in kids]
        stack.node.close()
        stack.node = None
        os.kill(stack.proc.pid, signal.SIGKILL)
        t0 = time.monotonic()
        while stack.survivors() and time.monotonic() - t0 < 2.0:
            time.sleep(0.02)
        took = time.monotonic() - t0
        assert not stack.survivors(), f"still running 2 s after the launcher died: {stack.survivors()}"
        assert took < 2.0
    finally:
        stack.kill()


# ------------------------------------------------------------------------------------------------ controller fault


def install_plugin(root: Path) -> str:
    """A throw-away distribution whose entry point names tests/reliability/raising_controller.py."""
    dist = root / "diffctl_faults-0.0.dist-info"
    dist.mkdir(parents=True)
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: diffctl-faults\nVersion: 0.0\n")
    (dist / "entry_points.txt").write_text(
        "[diffctl.controllers]\n"
        "diffctl_faults/RaisingController = tests.reliability.raising_controller:RaisingController\n"
    )
    return os.pathsep.join([str(root), str(REPO)])


def test_a_controller_raising_in_update_is_deactivated_the_others_keep_running(
    stack_env: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("PYTHONPATH", install_plugin(tmp_path / "site"))
    params = tmp_path / "faulty.yaml"
    params.write_text(
        "faulty_controller:\n  ros__parameters:\n    type: diffctl_faults/RaisingController\n    fail_after: 40\n"
    )
    stack = start_stack(tmp_path)
    procs = Procs()
    try:
        w = stack.watch
        drive(stack, 0.3, 0.0, 3, 0.3)
        spawner = procs.diffctl("spawn", "controller", "faulty_controller", "-p", str(params))
        out, _ = spawner.communicate(timeout=60)
        assert spawner.returncode == 0, out
        wait_until(
            lambda: stack.controllers().get("faulty_controller") == "inactive",
            30,
            "faulty_controller deactivated",
            stack,
        )
        wait_until(lambda: "injected fault" in launch_log(stack), 10, "the error logged", stack)
        log = launch_log(stack)
        assert re.search(
            r"controller 'faulty_controller' update\(\) raised .*injected fault after 40 cycles"
            r".*: deactivating it",
            log,
        ), log[-3000:]
        states = stack.controllers()
        assert all(states[c] == "active" for c in CONTROLLERS), states
        # The car still answers commands: the controllers and the loop run on.
        drive(stack, -0.2, 0.0, 3, -0.2)
        t = stack.clock_ns
        stack.wait_topic(ODOM, t + SEC)
        assert w.rate_hz(ODOM, t, t + SEC) >= 18
        assert stack.proc.poll() is None and "killed by" not in launch_log(stack) and "died" not in launch_log(stack)
        assert stack.stop(signal.SIGINT) == 0, stack.output()
    finally:
        procs.close()
        stack.kill()


# ------------------------------------------------------------------------------------------------ load


def test_flooding_publisher_and_slow_subscriber_leave_the_control_loop_on_period(
    stack_env: str, tmp_path: Path
) -> None:
    """At rtf:=1 (sim time = wall time): a publisher at 10× the 20 Hz control rate on cmd_vel and a subscriber
    that sleeps 0.2 s in every callback on the busiest topics."""
    from diffctl.bus import gz

    stack = start_stack(tmp_path, rtf="1")
    procs = Procs()
    stats: list[dict] = []
    try:
        w = stack.watch
        stats_sub = stack.node.session.declare_subscriber(
            gz.key("/world/empty/stats"), lambda s: stats.append(gz.decode(s.payload.to_bytes())[1])
        )
        wait_until(lambda: stats, 10, "world statistics", stack)
        slow = procs.start([sys.executable, "-m", "tests.reliability.bus_clients", "slow", "0.2"], cwd=REPO)
        flood = procs.start([sys.executable, "-m", "tests.reliability.bus_clients", "flood", "200", "0.4"], cwd=REPO)
        for p, word in ((slow, "slow subscriber ready"), (flood, "flood ready")):
            assert word in p.stdout.readline(), p.stdout.read() if p.poll() is not None else word
        wait_until(
            lambda: w.last(w.odom) and abs(w.last(w.odom).value[3] - 0.4) < 0.01,
            30,
            "the flood's command drives the car",
            stack,
        )
        t0_ns, t0_wall = stack.clock_ns, time.monotonic()
        stack.wait_sim(t0_ns + 5 * SEC, timeout_s=30)
        wall_s = time.monotonic() - t0_wall
        sent = [ln for ln in _lines(flood) if ln.startswith("flood sent")]
        assert sent and float(sent[-1].split("(")[1].split("/")[0]) >= 180, sent[-1:]

        # joint_states (from the manager's broadcaster): exactly one per 50 ms of sim time, by sequence number.
        with w.lock:
            js = [(t, s, g) for t, s, g in w.stamps["/joint_states"] if t0_ns <= t <= t0_ns + 5 * SEC]
        by_pub: dict[bytes, list[tuple[int, int]]] = {}
        for t, s, g in js:
            by_pub.setdefault(g, []).append((s, t))
        samples = sorted(max(by_pub.values(), key=len))
        assert len(samples) >= 50, f"only {len(samples)} joint_states in 5 s"
        bad = [
            (b[1] - a[1], b[0] - a[0])
            for a, b in itertools.pairwise(samples)
            if b[1] - a[1] != 50_000_000 * (b[0] - a[0])
        ]
        assert not bad, f"joint_states stamps off the 50 ms period: {bad[:5]}"
        # The sim kept real time: the manager inside it kept its period on the wall clock too.
        assert 5 / wall_s > 0.85, f"5 s of sim time took {wall_s:.2f} s of wall time"
        assert stats, "no world statistics"
        assert slow.poll() is None and flood.poll() is None
        stats_sub.undeclare()
        assert stack.stop(signal.SIGINT) == 0, stack.output()
    finally:
        procs.close()
        stack.kill()


def _lines(p: subprocess.Popen) -> list[str]:
    """What a running child printed so far (non-blocking)."""
    os.set_blocking(p.stdout.fileno(), False)
    try:
        return (p.stdout.read() or "").splitlines()
    except (BlockingIOError, TypeError):
        return []
