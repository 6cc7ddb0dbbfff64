"""The transport's own floor: bench/bus.py's TwistStamped round trip on bare zenoh-python, same run, same router.

Both ends open their sessions with diffctl's session configuration (`peer_config`) but use Zenoh's own
publisher and callback subscriber, with no diffctl code on the path: the payload is the serialized sample,
echoed as received. What the bus adds on top is `bus_rtt_*` minus `zenoh_raw_rtt_*`.
"""

from __future__ import annotations

import statistics
import struct
import subprocess
import sys
import textwrap
import threading
import time

PING_KEY = "bench/raw/ping"
PONG_KEY = "bench/raw/pong"

PONG = textwrap.dedent(f"""
    import threading
    import zenoh
    from diffctl.bus.session import peer_config
    s = zenoh.open(peer_config())
    pub = s.declare_publisher("{PONG_KEY}")
    sub = s.declare_subscriber("{PING_KEY}", lambda sample: pub.put(sample.payload))
    print("ready", flush=True)
    threading.Event().wait()
""")


def run(payload: bytes, samples: int, percentile) -> dict:
    """zenoh_raw_rtt_p50_us / _p99_us against the router DIFFCTL_ROUTER names (already running)."""
    import zenoh

    from diffctl.bus.session import peer_config

    pong = subprocess.Popen([sys.executable, "-c", PONG], stdout=subprocess.PIPE, text=True, start_new_session=True)
    session = None
    try:
        assert pong.stdout is not None and pong.stdout.readline().strip() == "ready"
        session = zenoh.open(peer_config())
        got = threading.Event()
        expect = [payload]
        sub = session.declare_subscriber(
            PONG_KEY, lambda sample: got.set() if sample.payload.to_bytes() == expect[0] else None)
        pub = session.declare_publisher(PING_KEY)
        deadline = time.monotonic() + 5
        while not got.is_set() and time.monotonic() < deadline:  # until the first echo: both ends matched
            pub.put(payload)
            got.wait(0.05)
        rtts: list[float] = []
        timeouts = 0
        for i in range(samples + 500):
            # The stamp's seconds (bytes 4-7 of the CDR) are this ping's number: only its own echo ends it.
            expect[0] = payload[:4] + struct.pack("<I", i) + payload[8:]
            got.clear()
            t0 = time.perf_counter()
            pub.put(expect[0])
            if not got.wait(1.0):
                timeouts += 1
                continue
            if i >= 500:  # warm-up, as bench/bus.py
                rtts.append((time.perf_counter() - t0) * 1e6)
        sub.undeclare()
        return {
            "zenoh_raw_rtt_p50_us": round(statistics.median(rtts), 1),
            "zenoh_raw_rtt_p99_us": round(percentile(rtts, 0.99), 1),
            "zenoh_raw_rtt_timeouts": timeouts,
        }
    finally:
        if session is not None:
            session.close()
        pong.kill()
        pong.wait()
