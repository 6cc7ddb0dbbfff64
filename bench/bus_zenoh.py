"""The transport's own floor: bench/bus.py's TwistStamped round trip on bare zenoh-python, same run, same router.

Both ends open their sessions with diffctl's session configuration (`peer_config`) but use Zenoh's own
publisher and callback subscriber, with no diffctl code on the path: the payload is the serialized sample,
echoed as received. What the bus adds on top is `bus_rtt_*` minus `zenoh_raw_rtt_*`; bench/bus.py takes both
in alternating blocks, so that the ratio compares the same moments of the machine.
"""

from __future__ import annotations

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


class RawPingPong:
    """A bare zenoh-python ping in this process and its pong in another, against the router DIFFCTL_ROUTER names
    (already running); `round_trips` times a block of them."""

    def __init__(self, payload: bytes) -> None:
        import zenoh

        from diffctl.bus.session import peer_config

        self._payload = payload
        self._pong = subprocess.Popen([sys.executable, "-c", PONG], stdout=subprocess.PIPE, text=True,
                                      start_new_session=True)
        self._session = None
        try:
            assert self._pong.stdout is not None and self._pong.stdout.readline().strip() == "ready"
            self._session = zenoh.open(peer_config())
            self._got = threading.Event()
            self._expect = [payload]
            got, expect = self._got, self._expect
            self._sub = self._session.declare_subscriber(
                PONG_KEY, lambda sample: got.set() if sample.payload.to_bytes() == expect[0] else None)
            self._pub = self._session.declare_publisher(PING_KEY)
            deadline = time.monotonic() + 5
            while not got.is_set() and time.monotonic() < deadline:  # until the first echo: both ends matched
                self._pub.put(payload)
                got.wait(0.05)
        except BaseException:
            self.close()
            raise

    def round_trips(self, count: int, first: int) -> tuple[list[float], int]:
        """`count` round trips (µs), numbered from `first`, and how many got no echo within 1 s."""
        payload, got, expect, put = self._payload, self._got, self._expect, self._pub.put
        rtts: list[float] = []
        timeouts = 0
        for i in range(first, first + count):
            # The stamp's seconds (bytes 4-7 of the CDR) are this ping's number: only its own echo ends it.
            expect[0] = payload[:4] + struct.pack("<I", i) + payload[8:]
            got.clear()
            t0 = time.perf_counter()
            put(expect[0])
            if not got.wait(1.0):
                timeouts += 1
                continue
            rtts.append((time.perf_counter() - t0) * 1e6)
        return rtts, timeouts

    def close(self) -> None:
        if self._session is not None:
            self._session.close()
            self._session = None
        self._pong.kill()
        self._pong.wait()
