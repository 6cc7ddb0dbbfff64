"""The simulator's gz publishers and subscribers on a real router: binary samples out, malformed ones dropped."""

from __future__ import annotations

import threading
import time

import numpy as np
import pytest

from diffctl.bus import gz, open_session
from diffctl.sim.log import Logger
from diffctl.sim.transport import SimTransport
from tests.waiting import wait_for


def test_publish_and_subscribe_binary_samples_and_drop_what_is_malformed(
    router: str, capsys: pytest.CaptureFixture[str]
) -> None:
    session = open_session()
    got: list[dict] = []
    lock = threading.Lock()

    def call_soon(fn) -> None:  # the sim thread's hand-over, run at once here
        with lock:
            fn()

    transport = SimTransport(session, call_soon, Logger("sim_under_test"))
    try:
        transport.subscribe("/scan_in", "gz.msgs.LaserScan", got.append)
        pub = transport.publisher("/scan_in", "gz.msgs.LaserScan")
        raw = session.declare_publisher(gz.key("/scan_in"))
        ranges = np.linspace(0.1, 9.9, 640)
        assert wait_for(lambda: pub.matched, 5.0)
        # Malformed: an old JSON sample, garbage, another type, a value with no encoding. None reaches the sim.
        raw.put(b'{"@type":"gz.msgs.LaserScan","ranges":[1.0]}')
        raw.put(b"\xc1\xc1\xc1")
        raw.put(gz.encode("gz.msgs.Twist", {"linear": {"x": 1.0}}))
        pub.publish({"ranges": ranges, "oops": object()})
        assert wait_for(lambda: bool(got), 5.0, lambda: pub.publish({"count": 640, "ranges": ranges}))
        assert got[0]["count"] == 640 and got[0]["ranges"].dtype == np.float64
        np.testing.assert_array_equal(got[0]["ranges"], ranges)
        assert all(set(g) == {"count", "ranges"} for g in got)
        raw.undeclare()
    finally:
        transport.close()
    err = capsys.readouterr().err
    assert "dropped a malformed message on gz topic /scan_in: malformed gz message" in err
    assert "dropped a sample on gz topic /scan_in: cannot encode gz.msgs.LaserScan" in err
    assert "Traceback" not in err


class _StalledLink:
    """A publisher whose first put blocks until released: a congested transmit thread."""

    def __init__(self) -> None:
        self.release = threading.Event()
        self.sent: list[bytes] = []

    def put(self, payload: bytes) -> None:
        if not self.sent:
            self.release.wait(10.0)
        self.sent.append(payload)


def test_outbox_under_a_frame_burst_drops_old_frames_never_the_clock() -> None:
    from diffctl.sim.transport import Outbox

    outbox = Outbox()
    link = _StalledLink()
    frame = bytes(2 * 1024 * 1024)  # a full-size rgbd frame
    clocks = [gz.clock(i * 10_000_000, 0, 0) for i in range(60)]
    try:
        outbox.put(link, clocks[0])
        for i in range(1, 60):
            outbox.put(link, frame)
            outbox.put(link, clocks[i])
        link.release.set()
        assert wait_for(lambda: clocks[-1] in link.sent, 10.0)
    finally:
        outbox.close()
    assert [p for p in link.sent if p != frame] == clocks  # every clock, in order
    frames = sum(p == frame for p in link.sent)
    assert 0 < frames <= Outbox.MAX_BYTES // len(frame) and outbox.dropped == 59 - frames


class _GilReleasingLink:
    """A publisher whose put gives up the GIL, as zenoh-python's does, and records what it got."""

    def __init__(self) -> None:
        self.sent: list[bytes] = []

    def put(self, payload: bytes) -> None:
        time.sleep(0)
        self.sent.append(payload)


def _physics_step(seconds: float) -> None:
    """CPU work that keeps the GIL but for the interpreter's forced switches, like `stepSimulation` in a loop."""
    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        pass


def test_outbox_loses_nothing_behind_a_sim_thread_running_flat_out() -> None:
    """At rtf 0 the sim thread never sleeps: a putting thread gets the GIL back only at the next forced switch
    (5 ms), so it cannot keep up on its own (with INLINE_BACKLOG out of reach, this test saw most samples
    dropped). The sim thread then puts the backlog itself, and every sample arrives, in order."""
    from diffctl.sim.transport import Outbox

    outbox = Outbox()
    link = _GilReleasingLink()
    expected = []
    try:
        for step in range(1500):
            outbox.hold()
            for k in range(3):  # a step's due samples: clock, IMU, joint states
                payload = f"{step}:{k}".encode()
                outbox.put(link, payload)
                expected.append(payload)
            outbox.release()
            _physics_step(50e-6)
        assert wait_for(lambda: len(link.sent) + outbox.dropped == len(expected), 10.0)
    finally:
        outbox.close()
    assert outbox.dropped == 0 and link.sent == expected
