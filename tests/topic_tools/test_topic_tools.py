"""topic_tools' nodes as real processes on a real router, against upstream's own tests (test_relay.cpp,
test_throttle.cpp, test_drop.cpp, test_mux.cpp: their inputs, parameters and expected counts) and its README's
command lines."""

from __future__ import annotations

import threading
import time
from typing import Any

import pytest

from tests import probe as bus_probe
from tests.waiting import wait_for

STRING = "std_msgs/msg/String"


class Probe:
    """A publisher on one topic and a raw subscriber on another, counting what comes through."""

    def __init__(self, node: Any, out_topic: str, out_type: str = STRING) -> None:
        self.node = node
        self.got: list[Any] = []
        self.raw: list[bytes] = []
        self.lock = threading.Lock()
        node.create_subscription(out_topic, out_type, self._keep)
        node.create_subscription(out_topic, out_type, self._keep_raw, raw=True)

    def _keep(self, m: Any) -> None:
        with self.lock:
            self.got.append(m)

    def _keep_raw(self, data: bytes) -> None:
        with self.lock:
            self.raw.append(bytes(data))

    def data(self) -> list[str]:
        with self.lock:
            return [m.data for m in self.got]


def _publisher(node: Any, topic: str, typename: str = STRING) -> Any:
    pub = node.create_publisher(topic, typename)
    assert wait_for(lambda: pub.subscription_count > 0, timeout_s=30), f"the tool never subscribed to {topic}"
    return pub


def test_relay_passes_any_type_byte_for_byte_and_lazy_waits_for_a_subscriber(router: str, procs) -> None:
    relay = procs.diffctl("run", "topic_tools", "relay", "/scan", "/scan_copy")
    lazy = procs.diffctl("run", "topic_tools", "relay", "/scan", "/scan_lazy", "--ros-args", "-p", "lazy:=true",
                         "-r", "__node:=lazy_relay")
    node = bus_probe.probe("relay_probe")
    try:
        scan_type = "sensor_msgs/msg/LaserScan"
        sent: list[bytes] = []
        node.create_subscription("/scan", scan_type, lambda d: sent.append(bytes(d)), raw=True)
        probe = Probe(node, "/scan_copy", scan_type)
        pub = node.create_publisher("/scan", scan_type)
        # the relay finds the publisher on the graph, then subscribes to it
        assert wait_for(lambda: pub.subscription_count >= 2, timeout_s=30)
        for i in range(100):
            pub.publish({"header": {"frame_id": "laser"}, "angle_increment": 0.01 * i,
                         "ranges": [float(i)] * 360})
            time.sleep(0.01)
        assert wait_for(lambda: len(probe.raw) >= 100, timeout_s=30), len(probe.raw)
        assert probe.raw == sent  # every message, in order, the same bytes
        # lazy: no subscription to /scan until /scan_lazy has a subscriber of its own
        assert wait_for(lambda: bool(node.graph.publishers("/scan_lazy")), timeout_s=30)
        time.sleep(0.3)
        assert len(node.graph.subscribers("/scan")) == 2  # the eager relay and this probe only
        Probe(node, "/scan_lazy", scan_type)
        assert wait_for(lambda: len(node.graph.subscribers("/scan")) == 3, timeout_s=30)
    finally:
        node.close()
    assert procs.stop(relay) == 0 and procs.stop(lazy) == 0


def test_throttle_by_messages_and_by_bytes(router: str, procs) -> None:
    # test_throttle.cpp: 1 message per second passes the first of a burst of four; 24 bytes per second over a
    # 1 s window passes two 20-byte "not dropped" strings of five.
    by_msgs = procs.diffctl("run", "topic_tools", "throttle", "messages", "/in_m", "1.0", "/out_m", "--ros-args",
                            "-p", "use_wall_clock:=true", "-r", "__node:=throttle_msgs")
    by_bytes = procs.diffctl("run", "topic_tools", "throttle", "bytes", "/in_b", "24", "1.0", "/out_b",
                             "--ros-args", "-p", "use_wall_clock:=true", "-r", "__node:=throttle_bytes")
    node = bus_probe.probe("throttle_probe")
    try:
        for suffix, burst, passing in (("m", ["not dropped", "dropped", "dropped", "dropped"], 1),
                                       ("b", ["not dropped", "not dropped", "dropped", "dropped", "dropped"], 2)):
            probe = Probe(node, f"/out_{suffix}")
            pub = _publisher(node, f"/in_{suffix}")
            time.sleep(1.1)  # a full period since the node started, as upstream's test waits
            for round_ in (1, 2):
                for text in burst:
                    pub.publish({"data": text})
                want = passing * round_
                assert wait_for(lambda p=probe, n=want: len(p.data()) >= n, timeout_s=30), probe.data()
                time.sleep(1.1)
            assert probe.data() == ["not dropped"] * (2 * passing)
    finally:
        node.close()
    assert procs.stop(by_msgs) == 0 and procs.stop(by_bytes) == 0


@pytest.mark.parametrize(("x", "y"), [(1, 2), (3, 5)])
def test_drop_x_of_every_y(router: str, procs, x: int, y: int) -> None:
    # test_drop.cpp's two cases: the first X of every Y are dropped
    drop = procs.diffctl("run", "topic_tools", "drop", "/in_d", str(x), str(y))
    node = bus_probe.probe("drop_probe")
    try:
        probe = Probe(node, "/in_d_drop")
        pub = _publisher(node, "/in_d")
        # Until the tool's output reaches this probe (discovery), messages may pass unseen: warm up first, then
        # the numbered ones must follow the pattern from whatever point of its count the tool is at.
        assert wait_for(lambda: bool(probe.data()), timeout_s=30, every=lambda: pub.publish({"data": "warm-up"}))
        time.sleep(0.2)
        with probe.lock:
            probe.got.clear()
        for i in range(20):
            pub.publish({"data": str(i)})
            time.sleep(0.02)  # within the tool's queue (depth 10, as upstream's QoS): none lost for being late
        patterns = [[str(i) for i in range(20) if (i + phase) % y >= x] for phase in range(y)]
        assert wait_for(lambda: probe.data() in patterns, timeout_s=30), probe.data()
    finally:
        node.close()
    assert procs.stop(drop) == 0


def test_mux_switches_inputs_through_its_services(router: str, procs) -> None:
    mux = procs.diffctl("run", "topic_tools", "mux", "/sel", "/a", "/b")
    node = bus_probe.probe("mux_probe")
    try:
        probe = Probe(node, "/sel")
        a, b = node.create_publisher("/a", STRING), node.create_publisher("/b", STRING)

        def feed_until(text: str) -> bool:
            return wait_for(lambda: text in probe.data(), timeout_s=30,
                            every=lambda: (a.publish({"data": "from a"}), b.publish({"data": "from b"})))

        assert feed_until("from a")
        assert "from b" not in probe.data()  # the first input is selected at start

        def call(name: str, values: dict) -> Any:
            cli = node.create_client(f"/mux/{name}", f"topic_tools_interfaces/srv/Mux{name.capitalize()}")
            assert cli.wait_for_service(30)
            return cli.call(values, timeout=10)

        r = call("select", {"topic": "/b"})
        assert (r.success, r.prev_topic) == (True, "/a")
        with probe.lock:
            probe.got.clear()
        assert feed_until("from b")
        time.sleep(0.2)
        with probe.lock:
            probe.got.clear()
        assert feed_until("from b")
        assert "from a" not in probe.data()
        assert call("select", {"topic": "/c"}).success is False  # not an input
        assert call("add", {"topic": "/c"}).success is True
        assert call("add", {"topic": "/c"}).success is False  # already one
        assert list(call("list", {}).topics) == ["/a", "/b", "/c"]
        assert call("delete", {"topic": "/b"}).success is False  # selected
        assert call("delete", {"topic": "/a"}).success is True
        assert list(call("list", {}).topics) == ["/b", "/c"]
        r = call("select", {"topic": "__none"})
        assert (r.success, r.prev_topic) == (True, "/b")
        with probe.lock:
            probe.got.clear()
        for _ in range(20):
            a.publish({"data": "from a"})
            b.publish({"data": "from b"})
            time.sleep(0.02)
        assert probe.data() == []
    finally:
        node.close()
    assert procs.stop(mux) == 0


def test_relay_field_as_its_readme_shows(router: str, procs) -> None:
    node = bus_probe.probe("relay_field_probe")
    try:
        chatter = node.create_publisher("/chatter", STRING)
        relay = procs.diffctl("run", "topic_tools", "relay_field", "/chatter", "/header", "std_msgs/Header",
                              "{stamp: {sec: 0, nanosec: 0}, frame_id: m.data}", "--wait-for-start")
        probe = Probe(node, "/header", "std_msgs/msg/Header")
        with probe.lock:
            pass
        assert wait_for(lambda: bool(probe.got), timeout_s=30, every=lambda: chatter.publish({"data": "hello"}))
        h = probe.got[-1]
        assert (h.frame_id, h.stamp.sec, h.stamp.nanosec) == ("hello", 0, 0)
    finally:
        node.close()
    assert procs.stop(relay) == 0
