"""A running launch of the whole stack for end-to-end tests, and what a test watches on the bus."""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import psutil

from diffctl.bus import gz
from diffctl.interfaces import types
from tests.probe import Probe


def yaw_of(q: Any) -> float:
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


@dataclass
class Sample:
    t_ns: int
    value: Any


@dataclass
class Watch:
    """Everything the tests read, stamped with sim time."""

    odom: list[Sample] = field(default_factory=list)  # (x, y, yaw, vx, wz)
    truth: list[Sample] = field(default_factory=list)  # (x, y, yaw)
    stamps: dict[str, list[tuple[int, int, bytes]]] = field(default_factory=dict)  # (sim ns, seq, publisher)
    lock: threading.Lock = field(default_factory=threading.Lock)

    def stamp(self, topic: str, t_ns: int, info: Any = None) -> None:
        seq, gid = (info.sequence_number, info.publisher_gid) if info is not None else (0, b"")
        with self.lock:
            self.stamps.setdefault(topic, []).append((t_ns, seq, gid))

    def last(self, series: list[Sample]) -> Sample | None:
        with self.lock:
            return series[-1] if series else None

    def at(self, series: list[Sample], t_ns: int) -> Sample:
        """The sample nearest to sim time t_ns."""
        with self.lock:
            return min(series, key=lambda s: abs(s.t_ns - t_ns))

    def reached_ns(self, topic: str) -> int:
        """The latest sim time stamped on `topic` so far (0: nothing yet)."""
        with self.lock:
            return max((t for t, _, _ in self.stamps.get(topic, [])), default=0)

    def recent_rate_hz(self, topic: str, span_s: float = 2.0) -> float:
        """`rate_hz` over the last `span_s` of sim time this topic has reached (bridged topics trail others)."""
        with self.lock:
            stamps = [t for t, _, _ in self.stamps.get(topic, [])]
        if not stamps:
            return 0.0
        end = max(stamps)
        return self.rate_hz(topic, end - int(span_s * 1e9), end + 1)

    def rate_hz(self, topic: str, start_ns: int, end_ns: int) -> float:
        """Publishing rate in sim time, from the publishers' sequence numbers (robust to samples this busy
        test process may drop): the fastest publisher's (Δseq / Δstamp) over the window."""
        by_pub: dict[bytes, list[tuple[int, int]]] = {}
        with self.lock:
            for t, seq, gid in self.stamps.get(topic, []):
                if start_ns <= t < end_ns:
                    by_pub.setdefault(gid, []).append((t, seq))
        best = 0.0
        for samples in by_pub.values():
            samples.sort()
            (t0, s0), (t1, s1) = samples[0], samples[-1]
            if t1 > t0:
                best = max(best, (s1 - s0) / ((t1 - t0) / 1e9))
        return best


class Stack:
    """`diffctl launch FILE rtf:=… viz:=false` in its own process group, plus a test node on its bus."""

    def __init__(
        self, launch_file: str | list[str], log_dir: Path, *args: str, rtf: str | None = "0",
        cwd: Path | None = None,
    ) -> None:
        """`launch_file`: a NAME, a PATH or [PKG, FILE]; `rtf`/`viz:=false` are passed to the project's own launch
        files (None: a user's file that declares neither)."""
        self.log_path = log_dir / "launch.out"
        self._out = open(self.log_path, "w")  # noqa: SIM115 — closed in stop()
        target = [launch_file] if isinstance(launch_file, str) else list(launch_file)
        ours = [f"rtf:={rtf}", "viz:=false"] if rtf is not None else []
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "diffctl", "launch", *target, *ours, *args,
             "--log-dir", str(log_dir), "--no-color"],
            stdout=self._out, stderr=subprocess.STDOUT, start_new_session=True, cwd=cwd,
        )
        self.node: Probe | None = None
        self.watch = Watch()
        self.clock_ns = 0
        self._cmd: dict | None = None
        self._cmd_pub = None
        self.last_cmd_ns = 0
        self._seen: dict[int, psutil.Process] = {}

    # ------------------------------------------------------------------ bus side
    def connect(self, timeout_s: float = 60.0) -> Probe:
        deadline = time.monotonic() + timeout_s
        while True:
            try:
                self.node = Probe("e2e_test")
                break
            except Exception:
                if time.monotonic() > deadline or self.proc.poll() is not None:
                    raise AssertionError(f"the launch never brought up its router:\n{self.output()}") from None
                time.sleep(0.1)
        w = self.watch
        n = self.node

        def stamped(topic: str):
            return lambda m, info: w.stamp(topic, types.time_ns(m.header.stamp), info)

        n.create_subscription("/clock", "rosgraph_msgs/msg/Clock", self._on_clock, with_info=True)
        n.create_subscription("/joint_states", "sensor_msgs/msg/JointState", stamped("/joint_states"),
                              with_info=True)
        n.create_subscription("/scan", "sensor_msgs/msg/LaserScan", stamped("/scan"), with_info=True)
        n.create_subscription(
            "/tf", "tf2_msgs/msg/TFMessage",
            lambda m, info: m.transforms and w.stamp("/tf", types.time_ns(m.transforms[0].header.stamp), info),
            with_info=True)
        self._truth_sub = n.session.declare_subscriber(gz.key("/model/robot/pose"), self._on_truth)
        return n

    def watch_odom(self, topic: str, typename: str = "nav_msgs/msg/Odometry") -> None:
        def on_odom(m: Any, info: Any) -> None:
            p, t = m.pose.pose, m.twist.twist
            with self.watch.lock:
                self.watch.odom.append(Sample(types.time_ns(m.header.stamp),
                                              (p.position.x, p.position.y, yaw_of(p.orientation), t.linear.x,
                                               t.angular.z)))
            self.watch.stamp(topic, types.time_ns(m.header.stamp), info)
            self._pace(types.time_ns(m.header.stamp))

        assert self.node is not None
        self.node.create_subscription(topic, typename, on_odom, with_info=True)

    def _on_truth(self, sample: Any) -> None:
        _, msg = gz.decode(sample.payload.to_bytes())
        poses = msg.get("pose") or []
        if not poses:
            return
        p = poses[0]
        pos, q = p.get("position", {}), p.get("orientation", {})
        yaw = math.atan2(2.0 * (q.get("w", 1.0) * q.get("z", 0.0) + q.get("x", 0.0) * q.get("y", 0.0)),
                         1.0 - 2.0 * (q.get("y", 0.0) ** 2 + q.get("z", 0.0) ** 2))
        t_ns = gz.stamp_ns(msg.get("header"))
        with self.watch.lock:
            self.watch.truth.append(Sample(t_ns, (pos.get("x", 0.0), pos.get("y", 0.0), yaw)))

    def _on_clock(self, m: Any, info: Any) -> None:
        self.clock_ns = max(self.clock_ns, types.time_ns(m.clock))
        self.watch.stamp("/clock", types.time_ns(m.clock), info)

    def _pace(self, t_ns: int) -> None:
        # Commands are paced by sim time — one per odometry sample, which comes straight from the controller
        # (the bridged /clock lags at high real-time factors) — so the test drives the same way whatever
        # real-time factor this machine reaches.
        self.clock_ns = max(self.clock_ns, t_ns)
        cmd, pub = self._cmd, self._cmd_pub
        if cmd is not None and pub is not None:
            # The stamp stays zero ("now" on the controller's clock): a stamp from this process could age
            # past cmd_vel_timeout on a busy machine before it arrives, and be dropped as stale.
            pub.publish(cmd)
            self.last_cmd_ns = t_ns

    def command(self, topic: str, typename: str, values: dict | None) -> None:
        """Publish `values` now and on every odometry sample from now on (None stops)."""
        assert self.node is not None
        if values is not None and (self._cmd_pub is None or self._cmd_pub.topic != topic):
            self._cmd_pub = self.node.create_publisher(topic, typename)
            deadline = time.monotonic() + 5
            while self._cmd_pub.subscription_count == 0 and time.monotonic() < deadline:
                time.sleep(0.01)
        self._cmd = types.new(typename, values) if values is not None else None
        if self._cmd is not None and not hasattr(self._cmd, "header"):
            self._cmd_pub.publish(self._cmd)

    def wait_sim(self, until_ns: int, timeout_s: float = 60.0) -> None:
        deadline = time.monotonic() + timeout_s
        while self.clock_ns < until_ns:
            assert time.monotonic() < deadline, f"sim time stuck at {self.clock_ns / 1e9:.3f} s"
            assert self.proc.poll() is None, f"the launch ended:\n{self.output()}"
            time.sleep(0.002)

    def wait_topic(self, topic: str, until_ns: int, timeout_s: float = 60.0) -> None:
        """Wait until samples stamped `until_ns` or later arrived on `topic`: each publisher's samples trail the
        simulator by their own delay (a publishing thread, the bridge), so /clock alone does not say they came."""
        deadline = time.monotonic() + timeout_s
        while self.watch.reached_ns(topic) < until_ns:
            assert time.monotonic() < deadline, f"{topic} stuck at {self.watch.reached_ns(topic) / 1e9:.3f} s"
            assert self.proc.poll() is None, f"the launch ended:\n{self.output()}"
            time.sleep(0.002)

    def wait_truth(self, until_ns: int, timeout_s: float = 30.0) -> None:
        """Wait until ground truth stamped `until_ns` or later arrived (it leaves the simulator by its own
        thread, so it may trail the controller's odometry)."""
        deadline = time.monotonic() + timeout_s
        while (last := self.watch.last(self.watch.truth)) is None or last.t_ns < until_ns:
            assert time.monotonic() < deadline, f"ground truth stuck at {last.t_ns / 1e9 if last else None} s"
            assert self.proc.poll() is None, f"the launch ended:\n{self.output()}"
            time.sleep(0.002)

    def controllers(self) -> dict[str, str]:
        assert self.node is not None
        cli = self.node.create_client("/controller_manager/list_controllers",
                                      "controller_manager_msgs/srv/ListControllers")
        if not cli.wait_for_service(0.5):
            return {}
        try:
            return {c.name: c.state for c in cli.call({}, timeout=2.0).controller}
        except Exception:
            return {}

    def wait_controllers_active(self, names: tuple[str, ...], timeout_s: float = 90.0) -> None:
        deadline = time.monotonic() + timeout_s
        while True:
            states = self.controllers()
            if all(states.get(n) == "active" for n in names):
                return
            self.descendants()
            assert time.monotonic() < deadline, f"controllers not active: {states}\n{self.output()}"
            assert self.proc.poll() is None, f"the launch ended:\n{self.output()}"
            time.sleep(0.1)

    # ------------------------------------------------------------------ process side
    def output(self) -> str:
        self._out.flush()
        return self.log_path.read_text()[-6000:]

    def descendants(self) -> list[psutil.Process]:
        """The launcher's descendants now (remembered, so a failing test can still kill them all)."""
        try:
            kids = psutil.Process(self.proc.pid).children(recursive=True)
        except psutil.NoSuchProcess:
            return []
        for k in kids:
            self._seen.setdefault(k.pid, k)
        return kids

    def survivors(self) -> list[psutil.Process]:
        return [p for p in self._seen.values() if p.is_running() and p.status() != psutil.STATUS_ZOMBIE]

    def stop(self, sig: int = signal.SIGINT, timeout_s: float = 20.0) -> int:
        if self.node is not None:
            self.node.close()
            self.node = None
        try:
            os.kill(self.proc.pid, sig)
            return self.proc.wait(timeout_s)
        finally:
            self.kill()

    def kill(self) -> None:
        for p in self.survivors():
            try:
                p.kill()
            except psutil.NoSuchProcess:
                pass
        if self.proc.poll() is None:
            try:
                os.killpg(self.proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            self.proc.wait()
        self._out.close()
