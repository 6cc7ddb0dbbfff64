"""How the cost grows with the number of cars: `diffctl launch fleet robots:=N` at rtf 0, for N = 1, 2, 5, 10.

Each car carries the tutorial's lidar (360 rays, 10 Hz) and IMU (100 Hz), both bridged to ROS (the bridge
subscribes, so both are computed), its controller manager in the simulator at 20 Hz with both controllers
active, and its own robot_state_publisher; one bridge and one visualizer serve them all. Per N:
`fleet_rtf_<N>` (median of the world's own real_time_factor over a few seconds at rtf 0, switched to once
every controller is active: the world runs at real time while the cars are spawned, so a world stepping flat
out does not starve the starting processes of CPU) and `fleet_rss_mb_<N>` (PSS of the launcher and all its
descendants: shared pages counted once). Derived: `fleet_rtf_ratio_10` (ten cars' RTF over one car's; target
≥ 0.2) and `fleet_rss_mb_per_car` (memory per added car from 1 to 10; target ≤ 30 MB).
Run: `python -m bench fleet`.
"""

from __future__ import annotations

import json
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import psutil

from bench.ports import free_port
from bench.stack import _tree_memory_mb

COUNTS = (1, 2, 5, 10)
READY = ("diffbot_base_controller", "joint_state_broadcaster")
MEASURE_S = 6.0
READY_TIMEOUT_S = 240.0


def _log_tail(log_dir: str) -> str:
    try:
        lines = (Path(log_dir) / "launch.log").read_text().splitlines()
    except OSError:
        return ""
    return ":\n" + "\n".join(lines[-8:])


def _all_active(node, count: int, clients: dict) -> bool:
    for k in range(1, count + 1):
        cli = clients.setdefault(k, node.create_client(f"/robot{k}/controller_manager/list_controllers",
                                                        "controller_manager_msgs/srv/ListControllers"))
        if not cli.service_is_ready():
            return False
        try:
            states = {c.name: c.state for c in cli.call({}, timeout=2.0).controller}
        except Exception:
            return False
        if any(states.get(n) != "active" for n in READY):
            return False
    return True


def measure(count: int) -> tuple[float, float, int]:
    """(median RTF at rtf:=0, PSS of the whole launch in MB, process count) with `count` cars."""
    from bench.probe import Probe
    from diffctl.bus import gz
    from diffctl.bus.session import close_session

    os.environ["DIFFCTL_ROUTER"] = f"tcp/127.0.0.1:{free_port()}"
    with tempfile.TemporaryDirectory(prefix="diffctl-bench-fleet-") as tmp:
        proc = subprocess.Popen(
            [sys.executable, "-m", "diffctl", "launch", "fleet", f"robots:={count}", "viz_port:=0", "--log-dir", tmp],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
        )
        node = None
        try:
            deadline = time.monotonic() + READY_TIMEOUT_S
            while node is None:
                try:
                    node = Probe("bench_fleet")
                except Exception:
                    if time.monotonic() > deadline or proc.poll() is not None:
                        raise RuntimeError(f"fleet of {count}: the launch never brought up its router"
                                           f"{_log_tail(tmp)}") from None
                    time.sleep(0.05)
            clients: dict = {}
            while not _all_active(node, count, clients):
                if proc.poll() is not None:
                    raise RuntimeError(f"fleet of {count}: the launch exited with {proc.returncode}{_log_tail(tmp)}")
                if time.monotonic() > deadline:
                    raise RuntimeError(f"fleet of {count}: controllers not all active in {READY_TIMEOUT_S:.0f} s")
                time.sleep(0.2)
            rtfs: list[float] = []
            sub = node.session.declare_subscriber(
                gz.key("/world/empty/stats"),
                lambda s: rtfs.append(float(gz.decode(s.payload.to_bytes())[1].get("real_time_factor", 0.0))))
            replies = list(node.session.get("gz/world/empty/control", payload=json.dumps({"rtf": 0}).encode(),
                                            timeout=5.0))
            if not any(r.ok is not None and json.loads(r.ok.payload.to_bytes()).get("ok") for r in replies):
                raise RuntimeError(f"fleet of {count}: the simulator did not switch to rtf 0")
            time.sleep(1.0)  # past the switch and the spawners' exits
            rtfs.clear()
            time.sleep(MEASURE_S)
            sub.undeclare()
            pss_mb, _ = _tree_memory_mb(proc.pid)
            processes = 1 + len(psutil.Process(proc.pid).children(recursive=True))
            values = [r for r in rtfs if r > 0]
            if not values:
                raise RuntimeError(f"fleet of {count}: the world published no statistics")
            return statistics.median(values), pss_mb, processes
        finally:
            if node is not None:
                node.close()
            close_session()
            if proc.poll() is None:
                os.kill(proc.pid, signal.SIGINT)
                try:
                    proc.wait(30)
                except subprocess.TimeoutExpired:
                    os.killpg(proc.pid, signal.SIGKILL)
                    proc.wait()


def run() -> dict:
    from diffctl.console import make_console, table

    out: dict[str, float] = {}
    rows = []
    failures = []
    for n in COUNTS:
        try:
            rtf, pss_mb, processes = measure(n)
        except RuntimeError as e:  # one fleet size that does not come up leaves the others measured
            failures.append(str(e))
            rows.append((str(n), "—", "—", "—", "—", "not measured"))
            continue
        out[f"fleet_rtf_{n}"] = round(rtf, 2)
        out[f"fleet_rss_mb_{n}"] = round(pss_mb, 1)
        one_rtf, one_mb = out.get("fleet_rtf_1"), out.get("fleet_rss_mb_1")
        rows.append((str(n), str(processes), f"{rtf:.1f}", "—" if one_rtf is None else f"{rtf / one_rtf:.2f}",
                     f"{pss_mb:.0f}", "—" if n == 1 or one_mb is None else f"{(pss_mb - one_mb) / (n - 1):.1f}"))
    last = COUNTS[-1]
    if f"fleet_rtf_{last}" in out and "fleet_rtf_1" in out:
        out[f"fleet_rtf_ratio_{last}"] = round(out[f"fleet_rtf_{last}"] / out["fleet_rtf_1"], 3)
        out["fleet_rss_mb_per_car"] = round((out[f"fleet_rss_mb_{last}"] - out["fleet_rss_mb_1"]) / (last - 1), 1)
    console = make_console(sys.stdout, width=150)
    for f in failures:
        console.print(f, markup=False)
    if not out:
        raise RuntimeError("no fleet size came up: " + "; ".join(failures))
    console.print(table(
        "fleet: cost growth (rtf:=0, lidar + IMU per car; targets: 10 cars ≥ 0.2× one car's RTF, ≤ 30 MB per car)",
        ["cars", "processes", "RTF", "× one car", "memory MB (PSS)", "MB per added car"], rows))
    return out


if __name__ == "__main__":
    print(run())
