"""Start-up timeline of `diffctl launch sim_control viz_port:=0`: seconds from exec to each step of the launch.

Reads the launcher's own output (each line timed as it arrives) and marks the steps that make up
`stack_launch_to_ready_s` (bench/stack.py): the launcher's first line, each process started, the simulator's
hardware, `create`'s "spawned", each spawner's first line, Loaded / Configured / activated and exit, and the
first /diffbot_base_controller/odom seen by this process. The fork server's start is read from /proc.

    python -m bench.startup_timeline [--runs N] [--no-fork-server] [--all]

--all prints every line of the launch output with its time, not only the marked steps.
"""

from __future__ import annotations

import os
import queue
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

from bench.ports import free_port

# (label, pattern on a launch output line); the first line matching a label marks it.
STEPS: tuple[tuple[str, str], ...] = (
    ("launcher: first line", r"All log files can be found"),
    ("robot_state_publisher started", r"\[robot_state_publisher\]: process started"),
    ("gz_sim started", r"\[gz_sim\]: process started"),
    ("create started", r"\[create\]: process started"),
    ("spawner diffbot started", r"\[spawner_diffbot_base_controller\]: process started"),
    ("parameter_bridge started", r"\[parameter_bridge\]: process started"),
    ("spawner diffbot: first line", r"^\[spawner_diffbot_base_controller\] "),
    ("gz_sim: hardware active", r"^\[gz_sim\] .*hardware .* is active"),
    ("create: spawned", r"^\[create\] .*spawned"),
    ("spawner diffbot: Loaded", r"^\[spawner_diffbot_base_controller\] .*Loaded"),
    ("spawner diffbot: Configured", r"^\[spawner_diffbot_base_controller\] .*: Configured diffbot"),
    ("gz_sim: diffbot active", r"^\[gz_sim\] .*activated diffbot_base_controller"),
    ("spawner diffbot finished", r"\[spawner_diffbot_base_controller\]: process has finished"),
    ("spawner jsb started", r"\[spawner_joint_state_broadcaster\]: process started"),
    ("spawner jsb: first line", r"^\[spawner_joint_state_broadcaster\] "),
    ("spawner jsb: Loaded", r"^\[spawner_joint_state_broadcaster\] .*Loaded"),
    ("gz_sim: jsb active", r"^\[gz_sim\] .*activated joint_state_broadcaster"),
    ("spawner jsb finished", r"\[spawner_joint_state_broadcaster\]: process has finished"),
)
DONE = "spawner jsb finished"


def _started_at(pid: int) -> float | None:
    """A process's start, as CLOCK_MONOTONIC seconds (10 ms resolution: clock ticks since boot)."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        return int(fields[19]) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return None


def _fork_server_start(launcher: int) -> float | None:
    try:
        children = Path(f"/proc/{launcher}/task/{launcher}/children").read_text().split()
    except OSError:
        return None
    for pid in map(int, children):
        try:
            if b"diffctl.supervision.zygote" in Path(f"/proc/{pid}/cmdline").read_bytes():
                return _started_at(pid)
        except OSError:
            continue
    return None


def run(*, show_all: bool = False, timeout_s: float = 30.0) -> dict[str, float]:
    """One launch; {step: seconds from exec}. Ends the launch with Ctrl-C once every step is seen."""
    from bench.probe import Probe
    from diffctl.bus.session import close_session

    os.environ["DIFFCTL_ROUTER"] = f"tcp/127.0.0.1:{free_port()}"
    marks: dict[str, float] = {}
    patterns = [(label, re.compile(p)) for label, p in STEPS]
    with tempfile.TemporaryDirectory(prefix="diffctl-timeline-") as tmp:
        # CLOCK_MONOTONIC counts from boot like /proc's start times, so both share one origin.
        t0 = time.clock_gettime(time.CLOCK_MONOTONIC)
        proc = subprocess.Popen(
            [sys.executable, "-m", "diffctl", "launch", "sim_control", "viz_port:=0", "--log-dir", tmp],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True, text=True,
        )
        odom = threading.Event()
        odom_at: list[float] = []

        def watch_odom() -> None:
            node = None
            while node is None and proc.poll() is None:
                try:
                    node = Probe("startup_timeline")
                except Exception:
                    time.sleep(0.02)
            if node is None:
                return

            def on_odom(_msg: object) -> None:
                if not odom_at:
                    odom_at.append(time.clock_gettime(time.CLOCK_MONOTONIC) - t0)
                    odom.set()

            node.create_subscription("/diffbot_base_controller/odom", "nav_msgs/msg/Odometry", on_odom)
            odom.wait(timeout_s)
            node.close()

        watcher = threading.Thread(target=watch_odom, daemon=True)
        watcher.start()
        lines: list[tuple[float, str]] = []
        try:
            assert proc.stdout is not None
            deadline = time.monotonic() + timeout_s
            zygote_seen = False
            # Read on a thread of its own: a step that never comes must end the run at the deadline, not block it.
            arrived: queue.Queue[str | None] = queue.Queue()
            threading.Thread(target=lambda: ([arrived.put(ln) for ln in proc.stdout], arrived.put(None)),
                             daemon=True).start()
            while DONE not in marks:
                try:
                    line = arrived.get(timeout=max(0.0, deadline - time.monotonic()))
                except queue.Empty:
                    break
                if line is None:
                    break
                t = time.clock_gettime(time.CLOCK_MONOTONIC) - t0
                lines.append((t, line.rstrip()))
                if not zygote_seen:
                    start = _fork_server_start(proc.pid)
                    if start is not None:
                        marks["fork server exec'd (/proc, ±10 ms)"] = start - t0
                        zygote_seen = True
                for label, pattern in patterns:
                    if label not in marks and pattern.search(line):
                        marks[label] = t
            odom.wait(max(0.0, deadline - time.monotonic()))
            if odom_at:
                marks["first odometry (this process)"] = odom_at[0]
        finally:
            if proc.poll() is None:
                os.kill(proc.pid, signal.SIGINT)
                try:
                    proc.wait(10)
                except subprocess.TimeoutExpired:
                    os.killpg(proc.pid, signal.SIGKILL)
                    proc.wait()
            close_session()
    if show_all:
        for t, line in lines:
            print(f"{t:7.3f}  {line[:160]}")
    return dict(sorted(marks.items(), key=lambda kv: kv[1]))


def main(argv: list[str]) -> None:
    if "--no-fork-server" in argv:
        os.environ["DIFFCTL_FORK_SERVER"] = "0"
    runs = int(argv[argv.index("--runs") + 1]) if "--runs" in argv else 1
    results = []
    for _ in range(runs):
        marks = run(show_all="--all" in argv)
        results.append(marks)
        load = os.getloadavg()[0]
        print(f"--- run {len(results)} (1-min load {load:.2f})")
        for label, t in marks.items():
            print(f"{t:7.3f}  {label}")
        ready = [marks.get("gz_sim: jsb active"), marks.get("first odometry (this process)")]
        if all(r is not None for r in ready):
            print(f"{max(ready):7.3f}  READY (both active, first odometry)")  # type: ignore[type-var]
        sys.stdout.flush()


if __name__ == "__main__":
    main(sys.argv[1:])
