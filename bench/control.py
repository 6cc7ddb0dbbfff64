"""Controller manager benchmark: 100 Hz on wall time, mock hardware, the tutorial's two controllers active.

The manager runs in this process (as `diffctl control manager` would) with diffbot_base_controller and
joint_state_broadcaster active — so every tick publishes /joint_states, /dynamic_joint_states and, at 50 Hz,
odometry and TF over a real router — while a teleop process sends TwistStamped at 20 Hz. Measured over
10 s: period jitter |Δt(wake) − 10 ms| p50/p99, and the cost of one read → update → write cycle.

Metrics (budget in bench/budget.py): `control_jitter_p99_ms`, `control_update_us` (the mean cost of one cycle, from
the wake-up to the end of write, wall; p50 and p99 are reported beside it, and `control_update_cpu_us`, the same
cycles' thread CPU time: on a shared machine the difference is time the loop waited, not work).
`control_update_us_<controller>` (no budget): the update cost of each of the other ros2_controllers diffctl provides,
measured alone (bench/control_controllers.py). The
control thread asks for SCHED_FIFO as ros2_control_node does; without the permission it runs at normal priority
and the jitter shows what the machine's scheduler gives.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from bench.ports import free_port, wait_port

REPO = Path(__file__).resolve().parent.parent
SDF = REPO / "description" / "my_diff_car_control.sdf"
CONFIG = REPO / "config" / "diff_drive_controller.yaml"


def run(duration_s: float = 10.0, rate_hz: int = 100) -> dict:
    from diffctl.bus.session import close_session
    from diffctl.control.ros2_control_node import ControlNode, ManagerOptions
    from diffctl.control.switching import STRICT

    port = free_port()
    endpoint = f"tcp/127.0.0.1:{port}"
    old_router = os.environ.get("DIFFCTL_ROUTER")
    os.environ["DIFFCTL_ROUTER"] = endpoint
    children: list[subprocess.Popen] = []

    def child(*args: str) -> subprocess.Popen:
        p = subprocess.Popen(
            [sys.executable, "-m", "diffctl", *args],
            start_new_session=True,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        children.append(p)
        return p

    node = None
    try:
        child("router", "--listen", endpoint)
        wait_port(port)
        opts = ManagerOptions(
            str(SDF), [str(CONFIG)], "mock_components/GenericSystem", {"calculate_dynamics": "true"}
        )
        node = ControlNode(opts, ["-p", "use_sim_time:=false", "-p", f"update_rate:={rate_hz}"])
        node.start()
        node.start_spinning()  # as ros2_control_node: without it no controller's subscription is served
        cm = node.cm
        assert cm is not None
        cm.set_controller_param("diffbot_base_controller", "type", "diff_drive_controller/DiffDriveController")
        cm.set_controller_param("diffbot_base_controller", "params_file", [str(CONFIG)])
        for name in ("diffbot_base_controller", "joint_state_broadcaster"):
            cm.load_controller(name)
            cm.configure_controller(name)
        ok, msg = cm.switch_controller(["diffbot_base_controller", "joint_state_broadcaster"], [], STRICT, True, 2.0)
        if not ok:
            raise RuntimeError(f"could not activate the controllers: {msg}")
        child(
            "topic",
            "pub",
            "/diffbot_base_controller/cmd_vel",
            "geometry_msgs/msg/TwistStamped",
            "{twist: {linear: {x: 0.2}, angular: {z: 0.1}}}",
            "--rate",
            "20",
        )
        time.sleep(1.0)  # warm-up: imports, first messages, the teleop's discovery
        node.stats.reset(capacity=int(duration_s * rate_hz * 2))
        time.sleep(duration_s)
        s = node.stats.summary(1.0 / rate_hz)
        updates = {n: mc.update_count for n, mc in cm.controllers.items()}
        odometry = cm.controllers["diffbot_base_controller"].instance.odometry
        if odometry is None or odometry.x_m == 0.0:  # the cycle timed must be the one that drives and publishes
            raise RuntimeError("diffbot_base_controller received no command: its odometry never moved")
    finally:
        if node is not None:
            node.shutdown()
        for p in children:
            try:
                os.killpg(p.pid, signal.SIGINT)
                p.wait(5)
            except (ProcessLookupError, subprocess.TimeoutExpired):
                os.killpg(p.pid, signal.SIGKILL)
        close_session()
        if old_router is None:
            os.environ.pop("DIFFCTL_ROUTER", None)
        else:
            os.environ["DIFFCTL_ROUTER"] = old_router
    return {
        **_other_controllers(),
        "control_jitter_p50_ms": round(s["jitter_p50_us"] / 1000, 4),
        "control_jitter_p99_ms": round(s["jitter_p99_us"] / 1000, 4),
        "control_jitter_max_ms": round(s["jitter_max_us"] / 1000, 3),
        "control_update_us": round(s["update_mean_us"], 1),
        "control_update_cpu_us": round(s["update_cpu_mean_us"], 1),
        "control_update_p50_us": round(s["update_p50_us"], 1),
        "control_update_p99_us": round(s["update_p99_us"], 1),
        "control_overruns": s["overruns"],
        "control_cycles": s["cycles"],
        "control_controller_updates": updates,
    }


def _other_controllers() -> dict:
    """control_update_us_<controller>, the other ros2_controllers' update cost, from a process of its own: the
    client's default context is initialized once per process, and this one's served the manager."""
    import json

    r = subprocess.run([sys.executable, "-m", "bench.control_controllers"], capture_output=True, text=True,
                       timeout=300, cwd=REPO)
    if r.returncode != 0:
        raise RuntimeError(f"bench.control_controllers exited {r.returncode}: {r.stderr.strip()[-2000:]}")
    return json.loads(r.stdout)


if __name__ == "__main__":
    import json

    print(json.dumps(run(), indent=2))
