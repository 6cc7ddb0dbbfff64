"""twist_mux and twist_stamper as real processes on a real router. twist_mux runs with its own system test's
configuration (test/system_config.yaml: three inputs, two locks) and is checked as its blackbox test checks
it — the highest-priority live input wins, a timed-out input gives way — plus its locks and `use_stamped`."""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import Any

import yaml

from tests.probe import Probe
from tests.waiting import wait_for

TWIST = "geometry_msgs/msg/Twist"
UPSTREAM_CONFIG = {  # twist_mux's test/system_config.yaml
    "topics": {"input1": {"topic": "vel_1", "timeout": 0.7, "priority": 5},
               "input2": {"topic": "vel_2", "timeout": 0.0, "priority": 1},
               "input3": {"topic": "vel_3", "timeout": 0.3, "priority": 10}},
    "locks": {"emergency_255": {"topic": "lock_1", "timeout": 0.5, "priority": 255},
              "emergency_10": {"topic": "lock_2", "timeout": 0.0, "priority": 10}},
}


class Out:
    def __init__(self, node: Probe, topic: str, typename: str) -> None:
        self.got: list[tuple[float, Any]] = []
        self.lock = threading.Lock()
        node.create_subscription(topic, typename, self._keep)

    def _keep(self, m: Any) -> None:
        with self.lock:
            self.got.append((time.monotonic(), m))

    def clear(self) -> None:
        with self.lock:
            self.got.clear()

    def last(self) -> Any:
        with self.lock:
            return self.got[-1][1] if self.got else None


def _twist(x: float = 0.0, r: float = 0.0) -> dict:
    return {"linear": {"x": x}, "angular": {"z": r}}


def test_priorities_timeouts_and_locks(router: str, procs, tmp_path: Path) -> None:
    params = tmp_path / "twist_mux.yaml"
    params.write_text(yaml.safe_dump({"twist_mux": {"ros__parameters": UPSTREAM_CONFIG}}))
    mux = procs.diffctl("run", "twist_mux", "twist_mux", "--ros-args", "--params-file", str(params))
    node = Probe("twist_mux_probe")
    try:
        out = Out(node, "/cmd_vel_out", TWIST)
        vel1, vel3 = node.create_publisher("/vel_1", TWIST), node.create_publisher("/vel_3", TWIST)
        lock1, lock2 = (node.create_publisher(t, "std_msgs/msg/Bool") for t in ("/lock_1", "/lock_2"))
        assert wait_for(lambda: all(p.subscription_count for p in (vel1, vel3, lock1, lock2)), timeout_s=30)
        # lock_1 has a 0.5 s timeout: a lock whose publisher stops locks everything. Keep it alive (and free).
        alive = threading.Event()
        alive.set()

        def heartbeat() -> None:
            while alive.is_set():
                lock1.publish({"data": False})
                time.sleep(0.1)

        beat = threading.Thread(target=heartbeat, daemon=True)
        beat.start()
        time.sleep(0.3)

        def sees(x: float, r: float, every: Any) -> bool:
            def match() -> bool:
                m = out.last()
                return m is not None and (m.linear.x, m.angular.z) == (x, r)
            return wait_for(match, timeout_s=30, every=every)

        # test_basic_with_priorities: input1 is used; input3 has priority over it; input3 silent → input1 again
        assert sees(2.0, 0.0, lambda: vel1.publish(_twist(2.0)))
        assert sees(0.0, 1.0, lambda: (vel1.publish(_twist(2.0)), vel3.publish(_twist(r=1.0))))
        last_vel3 = time.monotonic()
        out.clear()
        assert sees(2.0, 0.0, lambda: (vel1.publish(_twist(2.0)), time.sleep(0.02)))
        back = next(t for t, m in out.got if m.linear.x == 2.0)
        assert back - last_vel3 >= 0.3, f"input1 took over {back - last_vel3:.3f} s after input3's last message"
        # lock_2 (priority 10) masks input1 (5), not input3 (10)
        lock2.publish({"data": True})
        time.sleep(0.3)
        out.clear()
        for _ in range(10):
            vel1.publish(_twist(3.0))
            time.sleep(0.02)
        assert sees(0.0, 4.0, lambda: vel3.publish(_twist(r=4.0)))
        assert not [m for _, m in out.got if m.linear.x == 3.0]
        # lock_1's publisher stops: after its 0.5 s it locks everything (priority 255)
        alive.clear()
        beat.join()
        time.sleep(0.8)
        out.clear()
        for _ in range(15):
            vel3.publish(_twist(r=5.0))
            time.sleep(0.02)
        assert out.got == []
    finally:
        node.close()
    assert procs.stop(mux) == 0


def test_stamped_mux_and_the_stampers(router: str, procs, tmp_path: Path) -> None:
    params = tmp_path / "twist_mux.yaml"
    params.write_text(yaml.safe_dump({"twist_mux": {"ros__parameters": {
        "use_stamped": True, "topics": {"nav": {"topic": "nav_vel", "timeout": 0.5, "priority": 10}}}}}))
    mux = procs.diffctl("run", "twist_mux", "twist_mux", "--ros-args", "--params-file", str(params),
                        "-r", "cmd_vel_out:=/stamped_in")
    # nav Twist → twist_stamper → twist_mux (stamped) → twist_unstamper → Twist
    stamper = procs.diffctl("run", "twist_stamper", "twist_stamper", "--ros-args", "-p", "frame_id:=base_link",
                            "-r", "cmd_vel_in:=/raw", "-r", "cmd_vel_out:=/nav_vel")
    unstamper = procs.diffctl("run", "twist_stamper", "twist_unstamper", "--ros-args",
                              "-r", "cmd_vel_in:=/stamped_in", "-r", "cmd_vel_out:=/plain")
    node = Probe("stamper_probe")
    try:
        stamped = Out(node, "/stamped_in", "geometry_msgs/msg/TwistStamped")
        plain = Out(node, "/plain", TWIST)
        raw = node.create_publisher("/raw", TWIST)
        before = time.time_ns()
        assert wait_for(lambda: plain.last() is not None, timeout_s=30, every=lambda: raw.publish(_twist(0.7, 0.2)))
        s = stamped.last()
        assert s.header.frame_id == "base_link"
        assert s.header.stamp.sec * 1_000_000_000 + s.header.stamp.nanosec >= before - 1_000_000_000
        assert (s.twist.linear.x, s.twist.angular.z) == (0.7, 0.2)
        p = plain.last()
        assert (p.linear.x, p.angular.z) == (0.7, 0.2)
    finally:
        node.close()
    assert [procs.stop(p) for p in (mux, stamper, unstamper)] == [0, 0, 0]
