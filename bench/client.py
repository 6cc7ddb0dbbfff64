"""rclpy benchmark: the same user programs on diffctl's client library (over a router) and on the real rclpy
(Jazzy wheels, Fast DDS on loopback), in the same run.

Keys (`rclpy_*` ours, `rclpy_real_*` the real one): `*_rtt_p50_us` / `*_rtt_p99_us` (geometry_msgs/Twist
ping → pong node → back, each side a spinning rclpy node), `*_pubsub_msgs_per_s` (one node publishing Twist
as fast as it can, another counting in its subscription callback), `*_node_start_ms` (rclpy.init → node →
publisher → first publish returned, median of 5 fresh processes).
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import textwrap
import time

from bench.ports import free_port, wait_port

SAMPLES = 2000
WARMUP = 200
FLOOD_S = 3.0

PROGRAM = textwrap.dedent("""
    import json, sys, time
    t_start = time.perf_counter()
    import rclpy
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.node import Node
    from geometry_msgs.msg import Twist

    mode = sys.argv[1]
    t0 = time.perf_counter()
    rclpy.init()
    if mode == "start":
        node = Node("bench_start")
        pub = node.create_publisher(Twist, "/bench/start", 10)
        pub.publish(Twist())
        t1 = time.perf_counter()
        print(json.dumps({"start_ms": (t1 - t0) * 1e3, "import_ms": (t0 - t_start) * 1e3}), flush=True)
        sys.exit(0)
    node = Node("bench_" + mode)
    ex = SingleThreadedExecutor()
    ex.add_node(node)
    if mode == "pong":
        pub = node.create_publisher(Twist, "/bench/pong", 10)
        node.create_subscription(Twist, "/bench/ping", pub.publish, 10)
        print("ready", flush=True)
        ex.spin()
    elif mode == "ping":
        pub = node.create_publisher(Twist, "/bench/ping", 10)
        got = []
        node.create_subscription(Twist, "/bench/pong", got.append, 10)
        while pub.get_subscription_count() == 0 or node.count_publishers("/bench/pong") == 0:
            ex.spin_once(timeout_sec=0.01)
        end = time.monotonic() + 1.0
        while time.monotonic() < end:
            ex.spin_once(timeout_sec=0.01)
        msg = Twist()
        msg.linear.x = 0.5
        rtts = []
        for i in range(int(sys.argv[2])):
            got.clear()
            t0 = time.perf_counter()
            pub.publish(msg)
            deadline = t0 + 1.0
            while not got and time.perf_counter() < deadline:
                ex.spin_once(timeout_sec=0.1)
            if got and i >= int(sys.argv[3]):
                rtts.append((time.perf_counter() - t0) * 1e6)
        print(json.dumps({"rtts": rtts}), flush=True)
    elif mode == "count":
        count = [0]

        def on_msg(m):
            count[0] += 1

        node.create_subscription(Twist, "/bench/flood", on_msg, 10)
        print("ready", flush=True)
        while count[0] == 0:
            ex.spin_once(timeout_sec=0.1)
        t0, c0 = time.perf_counter(), count[0]
        end = t0 + float(sys.argv[2])
        while time.perf_counter() < end:
            ex.spin_once(timeout_sec=0.1)
        print(json.dumps({"msgs_per_s": (count[0] - c0) / (time.perf_counter() - t0)}), flush=True)
    elif mode == "flood":
        pub = node.create_publisher(Twist, "/bench/flood", 10)
        while pub.get_subscription_count() == 0:
            ex.spin_once(timeout_sec=0.01)
        time.sleep(0.5)
        msg = Twist()
        msg.linear.x = 0.5
        end = time.monotonic() + float(sys.argv[2])
        while time.monotonic() < end:
            for _ in range(50):
                pub.publish(msg)
    node.destroy_node()
    rclpy.try_shutdown()
""")


def _percentile(values: list[float], q: float) -> float:
    s = sorted(values)
    return s[min(len(s) - 1, int(q * len(s)))]


def _measure(cmd: list[str], env: dict[str, str], prefix: str) -> dict:
    procs: list[subprocess.Popen] = []

    def start(*args: str) -> subprocess.Popen:
        p = subprocess.Popen([*cmd, *args], env=env, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                             start_new_session=True, cwd="/tmp")
        procs.append(p)
        return p

    def result(p: subprocess.Popen, timeout: float = 120) -> dict:
        out, _ = p.communicate(timeout=timeout)
        lines = [ln for ln in out.splitlines() if ln.startswith("{")]
        if not lines:
            raise RuntimeError(f"{prefix}: a benchmark program printed nothing (exit {p.returncode})")
        return json.loads(lines[-1])

    try:
        starts = [result(start("start")) for _ in range(5)]
        pong = start("pong")
        assert pong.stdout.readline().strip() == "ready"
        rtts = result(start("ping", str(SAMPLES + WARMUP), str(WARMUP)))["rtts"]
        os.killpg(pong.pid, 9)
        counter = start("count", str(FLOOD_S))
        assert counter.stdout.readline().strip() == "ready"
        flood = start("flood", str(FLOOD_S + 2.0))
        rate = result(counter)["msgs_per_s"]
        os.killpg(flood.pid, 9)
    finally:
        for p in procs:
            try:
                os.killpg(p.pid, 9)
            except ProcessLookupError:
                pass
            p.wait()
    if not rtts:
        raise RuntimeError(f"{prefix}: no pong came back")
    return {
        f"{prefix}_rtt_p50_us": round(statistics.median(rtts), 1),
        f"{prefix}_rtt_p99_us": round(_percentile(rtts, 0.99), 1),
        f"{prefix}_rtt_samples": len(rtts),
        f"{prefix}_pubsub_msgs_per_s": round(rate),
        f"{prefix}_node_start_ms": round(statistics.median(s["start_ms"] for s in starts), 1),
        f"{prefix}_import_ms": round(statistics.median(s["import_ms"] for s in starts), 1),
    }


def _ours() -> dict:
    port = free_port()
    endpoint = f"tcp/127.0.0.1:{port}"
    router = subprocess.Popen([sys.executable, "-m", "diffctl", "router", "--listen", endpoint],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        wait_port(port)
        env = {**os.environ, "DIFFCTL_ROUTER": endpoint}
        return _measure([sys.executable, "-c", PROGRAM], env, "rclpy")
    finally:
        os.killpg(router.pid, 9)
        router.wait()


def _real() -> dict:
    from tests.oracle import jazzy_venv

    try:
        python = jazzy_venv.python()
    except jazzy_venv.OracleMissing as e:
        return {"rclpy_real_error": str(e)}
    return _measure([str(python), "-I", "-c", PROGRAM], jazzy_venv.env(), "rclpy_real")


def run() -> dict:
    out = _ours()
    try:
        out.update(_real())
    except Exception as e:  # the comparison row must not hide our own figures
        out["rclpy_real_error"] = f"{type(e).__name__}: {e}"
    # The goal as budget rows: ours ÷ the real rclpy's, from the same run (≤ 1 for times, ≥ 1 for the rate).
    for ratio, ours, real in (("rclpy_rtt_p50_vs_real", "rclpy_rtt_p50_us", "rclpy_real_rtt_p50_us"),
                              ("rclpy_node_start_vs_real", "rclpy_node_start_ms", "rclpy_real_node_start_ms"),
                              ("rclpy_pubsub_msgs_per_s_vs_real", "rclpy_pubsub_msgs_per_s",
                               "rclpy_real_pubsub_msgs_per_s")):
        if out.get(real):
            out[ratio] = round(out[ours] / out[real], 2)
    out["rclpy_load_avg_1min"] = round(os.getloadavg()[0], 2)
    return out


if __name__ == "__main__":
    t = time.monotonic()
    print(json.dumps(run(), indent=1), f"{time.monotonic() - t:.1f} s")
