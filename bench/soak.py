"""`make soak` / `python -m bench.soak [--minutes N]`: sim_control at rtf:=0 for a long time, driven by a script.

The car drives figure-eights (0.5 m/s, ±0.5 rad/s, one loop each way), with a stop every fifth eight in which
the publisher goes quiet and the controller must brake on cmd_vel_timeout. Commands are sent on every
odometry sample (stamp 0 = "now"), so the drive is paced by sim time whatever speed the machine reaches.

Sampled, and printed at the end (bench/results/soak.json too):
- resident memory (RSS and PSS) of the launcher and every descendant, every --sample-s; growth from the
  first samples after --warmup-minutes to the last samples. Fails if any process or the whole tree grows by
  more than 10 % (growth under 2 MB is allocator noise, not a leak, and is not counted);
- odometry vs ground truth: the motion over every 10 s window of sim time, in the robot's frame, from both.
  The tutorial's controller is open_loop, so odometry integrates the (limited) commands; the physics follows
  them with wheel slip and the 20 Hz command hold. Fails when a window disagrees by more than 5 % of the
  path plus 3 cm, or 5 % of the total turning plus 0.03 rad — the bounds the end-to-end test holds over 2 s — and
  reports the worst window at the start and at the end (agreement must not degrade with time);
- every process stays up (no death, no respawn), the real-time factor.
"""

from __future__ import annotations

import argparse
import bisect
import collections
import json
import math
import os
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import psutil

from bench.ports import free_port
from bench.soak_figures import MotionError, Pose2D, growth_percent, interpolate, motion_error

RESULTS = Path(__file__).resolve().parent / "results"
SEC = 1_000_000_000
CMD = "/diffbot_base_controller/cmd_vel"
ODOM = "/diffbot_base_controller/odom"
READY = ("diffbot_base_controller", "joint_state_broadcaster")
MEMORY_LIMIT_PERCENT = 10.0
MEMORY_NOISE_MB = 2.0
WINDOW_NS = 10 * SEC
MOTION_REL, MOTION_ABS_M, MOTION_ABS_RAD = 0.05, 0.03, 0.03
SPEED_M_S, TURN_RAD_S = 0.5, 0.5
LOOP_NS = int(math.tau / TURN_RAD_S * SEC)  # one circle of the eight
STOP_NS = 3 * SEC


def _yaw(q: Any) -> float:
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def drive_command(t_ns: int) -> tuple[float, float] | None:
    """The scripted figure-eight at sim time t_ns: (v, ω), or None while the publisher stays quiet."""
    cycle = 2 * LOOP_NS
    phase = t_ns % (5 * cycle + STOP_NS)
    if phase >= 5 * cycle:
        return None
    return SPEED_M_S, TURN_RAD_S if phase % cycle < LOOP_NS else -TURN_RAD_S


@dataclass
class Probe:
    """What the soak watches on the bus (callbacks run on Zenoh threads)."""

    lock: threading.Lock = field(default_factory=threading.Lock)
    odom: dict[int, Pose2D] = field(default_factory=dict)
    odom_order: collections.deque = field(default_factory=lambda: collections.deque(maxlen=400))
    truth: dict[int, Pose2D] = field(default_factory=dict)
    truth_order: collections.deque = field(default_factory=lambda: collections.deque(maxlen=1000))
    sim_ns: int = 0
    path_m: float = 0.0
    turned_rad: float = 0.0  # total |yaw change| of the ground truth
    last_truth: Pose2D | None = None
    stats: dict[str, Any] = field(default_factory=dict)

    def add(self, store: dict, order: collections.deque, t_ns: int, pose: Pose2D) -> None:
        if len(order) == order.maxlen:
            store.pop(order[0], None)
        order.append(t_ns)
        store[t_ns] = pose

    def on_odom(self, t_ns: int, pose: Pose2D) -> None:
        with self.lock:
            self.add(self.odom, self.odom_order, t_ns, pose)
            self.sim_ns = max(self.sim_ns, t_ns)

    def on_truth(self, t_ns: int, pose: Pose2D) -> None:
        with self.lock:
            self.add(self.truth, self.truth_order, t_ns, pose)
            if self.last_truth is not None:
                self.path_m += math.hypot(pose[0] - self.last_truth[0], pose[1] - self.last_truth[1])
                self.turned_rad += abs(math.remainder(pose[2] - self.last_truth[2], math.tau))
            self.last_truth = pose

    def anchor(self) -> tuple[int, Pose2D, Pose2D, float, float] | None:
        """The latest odometry pose with the ground truth interpolated to its stamp, and the path and turning so far."""
        with self.lock:
            times = list(self.truth_order)
            for t in reversed(self.odom_order):
                i = bisect.bisect_left(times, t)
                if i < len(times) and times[i] == t:
                    return t, self.odom[t], self.truth[t], self.path_m, self.turned_rad
                if 0 < i < len(times) and times[i] - times[i - 1] <= 100_000_000:
                    t0, t1 = times[i - 1], times[i]
                    truth = interpolate(self.truth[t0], self.truth[t1], (t - t0) / (t1 - t0))
                    return t, self.odom[t], truth, self.path_m, self.turned_rad
        return None


def _tree(pid: int) -> dict[int, psutil.Process]:
    root = psutil.Process(pid)
    return {p.pid: p for p in (root, *root.children(recursive=True))}


def _names(log: str) -> dict[int, str]:
    return {int(m[2]): m[1] for m in re.finditer(r"\[([\w.-]+)\] started \(pid (\d+)\)", log)}


def _memory(procs: dict[int, psutil.Process]) -> dict[int, tuple[float, float]]:
    out = {}
    for pid, p in procs.items():
        try:
            full = p.memory_full_info()
            out[pid] = (full.rss / 2**20, full.pss / 2**20)
        except psutil.NoSuchProcess:
            pass
    return out


def soak(minutes: float, warmup_minutes: float, sample_s: float, viz: bool) -> dict[str, Any]:
    from bench.probe import Probe as BusProbe
    from diffctl.bus import gz
    from diffctl.bus.session import close_session
    from diffctl.interfaces import types

    os.environ["DIFFCTL_ROUTER"] = f"tcp/127.0.0.1:{free_port()}"
    log_dir = Path(tempfile.mkdtemp(prefix="diffctl-soak-"))
    log_path = log_dir / "launch.out"
    args = ["rtf:=0", f"viz:={'true' if viz else 'false'}", f"viz_port:={free_port()}"]
    with open(log_path, "w") as out:
        proc = subprocess.Popen(
            [sys.executable, "-m", "diffctl", "launch", "sim_control", *args, "--log-dir", str(log_dir), "--no-color"],
            stdout=out,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
    probe = Probe()
    node = None
    try:
        deadline = time.monotonic() + 120
        while node is None:
            try:
                node = BusProbe("soak")
            except Exception:
                if time.monotonic() > deadline or proc.poll() is not None:
                    raise RuntimeError(f"the launch never came up; see {log_path}") from None
                time.sleep(0.1)
        pub = node.create_publisher(CMD, "geometry_msgs/msg/TwistStamped")
        cmd = types.new("geometry_msgs/msg/TwistStamped", {})

        def on_odom(m: Any) -> None:
            t = types.time_ns(m.header.stamp)
            p = m.pose.pose
            probe.on_odom(t, (p.position.x, p.position.y, _yaw(p.orientation)))
            vw = drive_command(t)
            if vw is not None:
                cmd.twist.linear.x, cmd.twist.angular.z = vw
                pub.publish(cmd)

        def on_truth(sample: Any) -> None:
            _, msg = gz.decode(sample.payload.to_bytes())
            poses = msg.get("pose") or []
            if poses:
                pos, q = poses[0].get("position", {}), poses[0].get("orientation", {})
                yaw = math.atan2(
                    2.0 * (q.get("w", 1.0) * q.get("z", 0.0) + q.get("x", 0.0) * q.get("y", 0.0)),
                    1.0 - 2.0 * (q.get("y", 0.0) ** 2 + q.get("z", 0.0) ** 2),
                )
                probe.on_truth(gz.stamp_ns(msg.get("header")), (pos.get("x", 0.0), pos.get("y", 0.0), yaw))

        def on_stats(sample: Any) -> None:
            probe.stats = gz.decode(sample.payload.to_bytes())[1]

        node.create_subscription(ODOM, "nav_msgs/msg/Odometry", on_odom)
        subs = [
            node.session.declare_subscriber(gz.key("/model/robot/pose"), on_truth),
            node.session.declare_subscriber(gz.key("/world/empty/stats"), on_stats),
        ]
        cli = node.create_client("/controller_manager/list_controllers", "controller_manager_msgs/srv/ListControllers")
        while True:
            states: dict[str, str] = {}
            if cli.wait_for_service(0.5):
                try:
                    states = {c.name: c.state for c in cli.call({}, timeout=2.0).controller}
                except Exception:
                    pass
            if all(states.get(n) == "active" for n in READY):
                break
            if time.monotonic() > deadline or proc.poll() is not None:
                raise RuntimeError(f"controllers never became active ({states}); see {log_path}")
            time.sleep(0.2)
        deadline = time.monotonic() + 60
        while not probe.stats or probe.anchor() is None:
            if time.monotonic() > deadline:
                raise RuntimeError(
                    f"no world statistics or no odometry with ground truth after 60 s "
                    f"(stats: {bool(probe.stats)}, odometry: {len(probe.odom)}, "
                    f"ground truth: {len(probe.truth)})"
                )
            time.sleep(0.1)
        names = _names(log_path.read_text())
        while viz and "rviz2" not in names.values():  # the visualizer starts once the controllers are active
            if time.monotonic() > deadline or proc.poll() is not None:
                raise RuntimeError(f"the visualizer never started; see {log_path}")
            time.sleep(0.2)
            names = _names(log_path.read_text())
        # One-shot processes (spawn entity, spawners) end on their own once their work is done: not tracked.
        procs = {
            pid: p for pid, p in _tree(proc.pid).items() if not names.get(pid, "").startswith(("spawner", "create"))
        }
        names[proc.pid] = "launcher"
        for pid, p in procs.items():
            if pid not in names:
                names[pid] = "launch guard" if "guard.py" in " ".join(p.cmdline()) else f"pid {pid}"
        print(
            f"soak: {len(procs)} processes up, driving figure-eights for {minutes:g} min "
            f"(memory baseline after {warmup_minutes:g} min)",
            flush=True,
        )

        t0 = time.monotonic()
        end = t0 + minutes * 60
        memory: dict[int, list[tuple[float, float]]] = {pid: [] for pid in procs}
        windows: list[tuple[int, float, MotionError]] = []  # (sim ns, wall s, error)
        last_anchor = probe.anchor()
        next_sample = t0 + warmup_minutes * 60
        next_report = t0 + 60
        lost: list[str] = []
        while time.monotonic() < end:
            time.sleep(0.2)
            now = time.monotonic()
            if proc.poll() is not None:
                lost.append(f"the launch exited with {proc.returncode}")
                break
            a = probe.anchor()
            if a is not None and last_anchor is not None and a[0] - last_anchor[0] >= WINDOW_NS:
                err = motion_error(
                    last_anchor[1], a[1], last_anchor[2], a[2], a[3] - last_anchor[3], a[4] - last_anchor[4]
                )
                windows.append((a[0], now - t0, err))
                last_anchor = a
            if now >= next_sample:
                next_sample += sample_s
                for pid, mem in _memory(procs).items():
                    memory[pid].append(mem)
                gone = [names.get(pid, str(pid)) for pid, p in procs.items() if not p.is_running()]
                if gone:
                    lost.append(f"processes gone: {', '.join(gone)}")
                    break
            if now >= next_report:
                next_report += 60
                total = sum(m[-1][1] for m in memory.values() if m)
                worst = max((w[2].position_m for w in windows[-6:]), default=0.0)
                print(
                    f"  {(now - t0) / 60:5.1f} min  sim {probe.sim_ns / 1e9:8.0f} s  "
                    f"rtf {probe.stats.get('real_time_factor', 0):5.1f}  PSS {total:6.1f} MB  "
                    f"odom-truth {worst * 100:.1f} cm/10 s",
                    flush=True,
                )
        wall_s = time.monotonic() - t0
        sim_s = probe.sim_ns / 1e9
        for s in subs:
            s.undeclare()
        node.close()
        node = None
        close_session()
        t_stop = time.monotonic()
        os.kill(proc.pid, signal.SIGINT)
        code = proc.wait(30)
        stop_s = time.monotonic() - t_stop
    finally:
        if node is not None:
            node.close()
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    log = log_path.read_text()
    lost += [ln for ln in log.splitlines() if re.search(r"process has died", ln)]
    return _figures(
        minutes,
        wall_s,
        sim_s,
        memory,
        names,
        windows,
        lost,
        code,
        stop_s,
        str(log_path),
    )


def _figures(
    minutes: float,
    wall_s: float,
    sim_s: float,
    memory: dict[int, list[tuple[float, float]]],
    names: dict[int, str],
    windows: list[tuple[int, float, MotionError]],
    lost: list[str],
    exit_code: int,
    stop_s: float,
    log: str,
) -> dict[str, Any]:
    per_process = {}
    failures: list[str] = []
    for pid, samples in memory.items():
        if len(samples) < 2:
            continue
        rss = [s[0] for s in samples]
        g = growth_percent(rss)
        name = names.get(pid, f"pid {pid}")
        per_process[name] = {
            "rss_first_mb": round(rss[0], 1),
            "rss_last_mb": round(rss[-1], 1),
            "growth_percent": round(g, 2),
        }
        if g > MEMORY_LIMIT_PERCENT and rss[-1] - rss[0] > MEMORY_NOISE_MB:
            failures.append(f"{name}: resident memory grew {g:.1f} % ({rss[0]:.1f} → {rss[-1]:.1f} MB)")
    n = min((len(s) for s in memory.values() if s), default=0)
    totals = [sum(s[i][1] for s in memory.values() if len(s) >= n) for i in range(n)]
    total_growth = growth_percent(totals)
    if total_growth > MEMORY_LIMIT_PERCENT and totals and totals[-1] - totals[0] > MEMORY_NOISE_MB:
        failures.append(f"all processes: memory (PSS) grew {total_growth:.1f} %")
    bad = [w for w in windows if not w[2].within(MOTION_REL, MOTION_ABS_M, MOTION_ABS_RAD)]
    if bad:
        w = bad[0]
        failures.append(
            f"{len(bad)} of {len(windows)} windows: odometry and ground truth disagree, first at sim "
            f"{w[0] / 1e9:.0f} s: {w[2].position_m * 100:.1f} cm, {w[2].yaw_rad:.3f} rad over "
            f"{w[2].path_m:.2f} m and {w[2].turned_rad:.2f} rad"
        )
    if not windows:
        failures.append("no odometry/ground-truth windows recorded")
    failures += lost
    if exit_code != 0:
        failures.append(f"the launch exited with {exit_code} on Ctrl-C")
    k = max(1, len(windows) // 10)
    first, last = windows[:k], windows[-k:]
    return {
        "minutes": minutes,
        "wall_s": round(wall_s, 1),
        "sim_s": round(sim_s, 1),
        "real_time_factor": round(sim_s / wall_s, 2) if wall_s else 0.0,
        "memory_total_pss_first_mb": round(totals[0], 1) if totals else None,
        "memory_total_pss_last_mb": round(totals[-1], 1) if totals else None,
        "memory_total_growth_percent": round(total_growth, 2),
        "memory_samples": n,
        "memory_per_process": per_process,
        "odom_truth_windows": len(windows),
        "odom_truth_worst_cm_first_10pct": round(max((w[2].position_m for w in first), default=0) * 100, 2),
        "odom_truth_worst_cm_last_10pct": round(max((w[2].position_m for w in last), default=0) * 100, 2),
        "odom_truth_worst_cm": round(max((w[2].position_m for w in windows), default=0) * 100, 2),
        "odom_truth_worst_rad": round(max((w[2].yaw_rad for w in windows), default=0), 4),
        "ctrl_c_to_exit_s": round(stop_s, 2),
        "launch_log": log,
        "failures": failures,
        "ok": not failures,
    }


def report(fig: dict[str, Any]) -> None:
    from diffctl.console import make_console, table

    console = make_console(sys.stdout, width=150)
    rows = [(k, v) for k, v in fig.items() if k not in ("memory_per_process", "failures", "ok")]
    console.print(table("soak: sim_control at rtf:=0, figure-eights", ["figure", "value"], rows))
    console.print(
        table(
            "resident memory per process (after warm-up)",
            ["process", "first MB", "last MB", "growth %"],
            [
                (n, p["rss_first_mb"], p["rss_last_mb"], p["growth_percent"])
                for n, p in sorted(fig["memory_per_process"].items())
            ],
        )
    )
    for f in fig["failures"]:
        console.print(f"FAIL: {f}", markup=False)
    console.print("soak: " + ("held" if fig["ok"] else "FAILED"), markup=False)


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(
        prog="python -m bench.soak",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog="Example: python -m bench.soak --minutes 5",
    )
    ap.add_argument("--minutes", type=float, default=30.0, help="wall time to drive (default 30)")
    ap.add_argument(
        "--warmup-minutes",
        type=float,
        default=None,
        help="minutes before the memory baseline (default: a tenth of --minutes, at most 3)",
    )
    ap.add_argument("--sample-s", type=float, default=10.0, help="seconds between memory samples (default 10)")
    ap.add_argument("--no-viz", action="store_true", help="leave the visualizer out (viz:=false)")
    a = ap.parse_args(argv)
    if not (a.minutes > 0 and a.sample_s > 0):
        ap.error("--minutes and --sample-s must be positive")
    # SIGTERM/SIGHUP (a CI timeout, a closed terminal) end the run through the same cleanup as Ctrl-C.
    for sig in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, signal.default_int_handler)
    warmup = a.warmup_minutes if a.warmup_minutes is not None else min(3.0, a.minutes / 10)
    fig = soak(a.minutes, warmup, a.sample_s, viz=not a.no_viz)
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / "soak.json").write_text(
        json.dumps({"when": time.strftime("%Y-%m-%dT%H:%M:%S%z"), **fig}, indent=2) + "\n"
    )
    report(fig)
    return 0 if fig["ok"] else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
