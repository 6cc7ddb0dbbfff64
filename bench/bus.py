"""Bus benchmark: TwistStamped round trip between two processes through the router, and decoded throughput.

Metrics (budget in bench/budget.py): `bus_rtt_p50_us`, `bus_rtt_p99_us` (as ratios to bare zenoh-python's,
`bus_rtt_p50_vs_zenoh` and `bus_rtt_p99_vs_zenoh`), `bus_throughput_msgs_s` (≥ 100,000,
one-way, every message deserialized by the receiver, over the window from the sender's start to the last
message received: `bus_throughput_window_s`, `bus_flood_drain_s` of it after the sender stopped). Each ping
carries its own stamp and only its own echo ends it; one with no echo within 1 s is counted
(`bus_rtt_timeouts`), not dropped silently, and an echo that arrives after its timeout ends nothing. The same
harness then runs on Cyclone DDS's Python binding (bench/bus_dds.py, `cyclonedds_*` keys) so that both are
measured in the same run, on the same load, and on bare zenoh-python with the same session configuration
(bench/bus_zenoh.py, `zenoh_raw_rtt_*`): the transport's floor under the bus.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import textwrap
import threading
import time

from bench.drain import drained
from bench.ports import free_port, wait_port

SAMPLES = 5000
WARMUP = 500
BLOCK = 250  # round trips of one kind before the other kind's turn
TYPE = "geometry_msgs/msg/TwistStamped"

PONG = textwrap.dedent(f"""
    from bench.probe import Probe
    n = Probe("bench_pong")
    pub = n.create_publisher("/bench/pong", "{TYPE}")
    n.create_subscription("/bench/ping", "{TYPE}", pub.publish_raw, raw=True)
    print("ready", flush=True)
    n.spin()
""")

FLOOD = textwrap.dedent(f"""
    import sys, time
    from bench.probe import Probe
    from diffctl.interfaces import types
    n = Probe("bench_flood")
    pub = n.create_publisher("/bench/flood", "{TYPE}")
    raw = types.serialize(types.new("{TYPE}", {{"twist": {{"linear": {{"x": 0.5}}}}}}), "{TYPE}")
    while pub.subscription_count == 0:
        time.sleep(0.01)
    time.sleep(0.2)
    print("go", flush=True)
    end = time.monotonic() + float(sys.argv[1])
    sent = 0
    while time.monotonic() < end:
        for _ in range(100):
            pub.publish_raw(raw)
        sent += 100
    print(f"sent {{sent}}", flush=True)
""")


def percentile(values: list[float], q: float) -> float:
    s = sorted(values)
    return s[min(len(s) - 1, int(q * len(s)))]


def run() -> dict:
    from bench import bus_zenoh
    from bench.probe import Probe
    from diffctl.bus.session import close_session
    from diffctl.interfaces import types

    port = free_port()
    os.environ["DIFFCTL_ROUTER"] = f"tcp/127.0.0.1:{port}"
    router = subprocess.Popen([sys.executable, "-m", "diffctl", "router"], stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, start_new_session=True)
    procs = [router]
    try:
        wait_port(port)
        pong = subprocess.Popen([sys.executable, "-c", PONG], stdout=subprocess.PIPE, text=True,
                                start_new_session=True)
        procs.append(pong)
        assert pong.stdout.readline().strip() == "ready"
        node = Probe("bench_ping")
        got = threading.Event()
        expect = [b""]
        node.create_subscription("/bench/pong", TYPE, lambda d: got.set() if bytes(d) == expect[0] else None,
                                 raw=True)
        pub = node.create_publisher("/bench/ping", TYPE)
        msg = types.new(TYPE, {"twist": {"linear": {"x": 0.5}}})
        while pub.subscription_count == 0:
            time.sleep(0.01)
        time.sleep(0.3)
        def bus_round_trips(count: int, first: int) -> tuple[list[float], int]:
            times: list[float] = []
            lost = 0
            for i in range(first, first + count):
                msg.header.stamp.sec = i  # this ping's own echo, told apart from a late one of an earlier ping
                expect[0] = types.serialize(msg, TYPE)
                got.clear()
                t0 = time.perf_counter()
                pub.publish(msg)  # serialize + put, as a real publisher does
                if not got.wait(1.0):
                    lost += 1
                    continue
                times.append((time.perf_counter() - t0) * 1e6)
            return times, lost

        raw_pingpong = bus_zenoh.RawPingPong(types.serialize(msg, TYPE))
        try:
            # Warm-up, then the bus and bare Zenoh in alternating blocks: a machine whose speed drifts (a shared
            # VM's does, by tens of percent within a minute) weighs on both alike, so their ratio is the bus's.
            bus_round_trips(WARMUP, 0)
            raw_pingpong.round_trips(WARMUP, 0)
            rtts: list[float] = []
            raw_rtts: list[float] = []
            timeouts = raw_timeouts = 0
            for first in range(WARMUP, WARMUP + SAMPLES, BLOCK):
                times, lost = bus_round_trips(BLOCK, first)
                rtts += times
                timeouts += lost
                times, lost = raw_pingpong.round_trips(BLOCK, first)
                raw_rtts += times
                raw_timeouts += lost
        finally:
            raw_pingpong.close()

        count = [0]

        def on_flood(m) -> None:
            # No lock: zenoh-python calls one subscriber's callback on one thread, the only writer; the main
            # thread only reads. (A lock here cost every sample an acquire and a release.)
            count[0] += 1

        node.create_subscription("/bench/flood", TYPE, on_flood)  # decoded into a message every time
        duration = 3.0
        flood = subprocess.Popen([sys.executable, "-c", FLOOD, str(duration)], stdout=subprocess.PIPE, text=True,
                                 start_new_session=True)
        procs.append(flood)
        assert flood.stdout.readline().strip() == "go"
        start_count = count[0]
        t0 = time.monotonic()
        sent_line = flood.stdout.readline().split()
        t_sent = time.monotonic()
        final, t_last = drained(lambda: count[0])
        flood.wait(10)
        received = final - start_count
        elapsed = max(t_last, t_sent) - t0
        node.close()
        result = {
            "bus_rtt_p50_us": round(statistics.median(rtts), 1),
            "bus_rtt_p99_us": round(percentile(rtts, 0.99), 1),
            "bus_rtt_samples": len(rtts),
            "bus_rtt_timeouts": timeouts,
            "bus_throughput_msgs_s": round(received / elapsed),
            "bus_throughput_window_s": round(elapsed, 3),
            "bus_flood_drain_s": round(max(0.0, t_last - t_sent), 3),
            # What the publisher got out; the rest was dropped (reliable keep-last 10 drops under congestion).
            "bus_flood_sent_msgs_s": round(int(sent_line[1]) / duration) if len(sent_line) == 2 else 0,
            "bus_load_avg_1min": round(os.getloadavg()[0], 2),  # the machine is shared: say how busy it was
            "zenoh_raw_rtt_p50_us": round(statistics.median(raw_rtts), 1),
            "zenoh_raw_rtt_p99_us": round(percentile(raw_rtts, 0.99), 1),
            "zenoh_raw_rtt_timeouts": raw_timeouts,
        }
    finally:
        close_session()
        for p in reversed(procs):
            try:
                os.killpg(p.pid, 9)
            except ProcessLookupError:
                pass
            p.wait()
    result.update(_cyclonedds())
    return result


def _cyclonedds() -> dict:
    """The Cyclone DDS row of the same run; if cyclonedds cannot be imported or run, why (as a string)."""
    try:
        from bench import bus_dds
    except ImportError as e:
        return {"cyclonedds_error": f"cyclonedds not available: {e}"}
    try:
        return bus_dds.run()
    except Exception as e:
        return {"cyclonedds_error": f"{type(e).__name__}: {e}"}


if __name__ == "__main__":
    print(run())
