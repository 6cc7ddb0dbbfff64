"""The same bus benchmark on Eclipse Cyclone DDS's Python binding (`cyclonedds` from PyPI), for comparison.

Same harness as bench/bus.py: two processes on loopback; the round trip is timed from before the write
(which serializes) until a listener in the ping process sees the echo; throughput counts samples decoded
(taken as IDL objects) by the receiver while another process writes back to back. Same message shape:
a TwistStamped under its DDS name, QoS as ROS 2's default (reliable, volatile, keep last 10). Cyclone is
confined to loopback with no multicast by the CYCLONEDDS_URI written here, in a domain of its own.
(No `from __future__ import annotations`: cyclonedds resolves the IDL field annotations at run time.)
"""


import os
import random
import statistics
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from cyclonedds.core import Listener, Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl.types import float64, int32, uint32
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from cyclonedds.util import duration

from bench.bus import percentile
from bench.drain import drained

SAMPLES = 5000
WARMUP = 500

# Loopback only, unicast discovery to 127.0.0.1: nothing leaves the machine, nothing is multicast.
CONFIG = (
    "<CycloneDDS><Domain Id='any'><General><Interfaces><NetworkInterface name='lo'/></Interfaces>"
    "<AllowMulticast>false</AllowMulticast></General><Discovery><ParticipantIndex>auto</ParticipantIndex>"
    "<MaxAutoParticipantIndex>20</MaxAutoParticipantIndex><Peers><Peer address='127.0.0.1'/></Peers>"
    "</Discovery></Domain></CycloneDDS>"
)



@dataclass
class Time(IdlStruct, typename="builtin_interfaces::msg::dds_::Time_"):
    sec: int32 = 0
    nanosec: uint32 = 0


@dataclass
class Header(IdlStruct, typename="std_msgs::msg::dds_::Header_"):
    stamp: Time = field(default_factory=Time)
    frame_id: str = ""


@dataclass
class Vector3(IdlStruct, typename="geometry_msgs::msg::dds_::Vector3_"):
    x: float64 = 0.0
    y: float64 = 0.0
    z: float64 = 0.0


@dataclass
class Twist(IdlStruct, typename="geometry_msgs::msg::dds_::Twist_"):
    linear: Vector3 = field(default_factory=Vector3)
    angular: Vector3 = field(default_factory=Vector3)


@dataclass
class TwistStamped(IdlStruct, typename="geometry_msgs::msg::dds_::TwistStamped_"):
    header: Header = field(default_factory=Header)
    twist: Twist = field(default_factory=Twist)


MSG = TwistStamped(twist=Twist(linear=Vector3(x=0.5)))


class _Endpoints:
    """One participant in `domain` with ROS 2's default QoS on every topic (names as rmw_cyclonedds maps them)."""

    def __init__(self, domain: int) -> None:
        os.environ["CYCLONEDDS_URI"] = CONFIG  # read when the process's first participant is created
        self.qos = Qos(Policy.Reliability.Reliable(max_blocking_time=duration(milliseconds=100)),
                       Policy.Durability.Volatile, Policy.History.KeepLast(10))
        self.dp = DomainParticipant(domain)
        self.keep: list = []

    def writer(self, name: str) -> DataWriter:
        return DataWriter(self.dp, Topic(self.dp, name, TwistStamped, qos=self.qos), qos=self.qos)

    def reader(self, name: str, on_data: Callable[[DataReader], None]) -> DataReader:
        class _Listener(Listener):
            def on_data_available(self, r: DataReader) -> None:
                on_data(r)

        r = DataReader(self.dp, Topic(self.dp, name, TwistStamped, qos=self.qos), qos=self.qos,
                       listener=_Listener())
        self.keep.append(r)
        return r

    @staticmethod
    def wait_matched(w: DataWriter) -> None:
        while not w.get_matched_subscriptions():
            time.sleep(0.01)


def _pong(domain: int) -> None:
    ep = _Endpoints(domain)
    pong = ep.writer("rt/bench/pong")

    def echo(r: DataReader) -> None:
        for s in r.take(N=100):
            pong.write(s)

    ep.reader("rt/bench/ping", echo)
    ep.wait_matched(pong)
    print("ready", flush=True)
    time.sleep(3600)


def _flood(domain: int, duration_s: float) -> None:
    ep = _Endpoints(domain)
    w = ep.writer("rt/bench/flood")
    ep.wait_matched(w)
    time.sleep(0.2)
    print("go", flush=True)
    end = time.monotonic() + duration_s
    sent = 0
    while time.monotonic() < end:
        for _ in range(100):
            w.write(MSG)
        sent += 100
    print(f"sent {sent}", flush=True)


def run() -> dict:
    domain = random.randint(100, 220)  # a domain of this run's own: concurrent runs do not see each other
    ep = _Endpoints(domain)
    role = [sys.executable, "-m", "bench.bus_dds"]
    procs: list[subprocess.Popen] = []
    try:
        pong = subprocess.Popen([*role, "pong", str(domain)], stdout=subprocess.PIPE, text=True,
                                start_new_session=True)
        procs.append(pong)
        ping_w = ep.writer("rt/bench/ping")
        got = threading.Event()
        expect = [-1]

        def on_pong(r: DataReader) -> None:
            if any(s.header.stamp.sec == expect[0] for s in r.take(N=100)):
                got.set()

        ep.reader("rt/bench/pong", on_pong)
        if pong.stdout.readline().strip() != "ready":
            raise RuntimeError("the Cyclone DDS pong process did not start")
        ep.wait_matched(ping_w)
        time.sleep(0.3)
        rtts: list[float] = []
        timeouts = 0
        for i in range(SAMPLES + WARMUP):
            MSG.header.stamp.sec = expect[0] = i  # only this ping's own echo ends it
            got.clear()
            t0 = time.perf_counter()
            ping_w.write(MSG)  # serialize + write, as for the Zenoh row
            if not got.wait(1.0):
                timeouts += 1
                continue
            if i >= WARMUP:
                rtts.append((time.perf_counter() - t0) * 1e6)

        count = [0]
        lock = threading.Lock()

        def on_flood(r: DataReader) -> None:
            while n := len(r.take(N=32)):  # every sample deserialized into a TwistStamped object
                with lock:
                    count[0] += n

        ep.reader("rt/bench/flood", on_flood)
        duration = 3.0
        flood = subprocess.Popen([*role, "flood", str(domain), str(duration)], stdout=subprocess.PIPE, text=True,
                                 start_new_session=True)
        procs.append(flood)
        if flood.stdout.readline().strip() != "go":
            raise RuntimeError("the Cyclone DDS flood process did not start")
        with lock:
            start_count = count[0]
        t0 = time.monotonic()
        sent_line = flood.stdout.readline().split()
        t_sent = time.monotonic()
        final, t_last = drained(lambda: count[0])
        flood.wait(10)
        received = final - start_count
        elapsed = max(t_last, t_sent) - t0
        sent = int(sent_line[1]) if len(sent_line) == 2 else 0
        return {
            "cyclonedds_sent_msgs_s": round(sent / duration),
            "cyclonedds_rtt_p50_us": round(statistics.median(rtts), 1),
            "cyclonedds_rtt_p99_us": round(percentile(rtts, 0.99), 1),
            "cyclonedds_rtt_samples": len(rtts),
            "cyclonedds_rtt_timeouts": timeouts,
            "cyclonedds_throughput_msgs_s": round(received / elapsed),
            "cyclonedds_throughput_window_s": round(elapsed, 3),
        }
    finally:
        for p in reversed(procs):
            try:
                os.killpg(p.pid, 9)
            except ProcessLookupError:
                pass
            p.wait()


if __name__ == "__main__":
    if sys.argv[1:2] == ["pong"]:
        _pong(int(sys.argv[2]))
    elif sys.argv[1:2] == ["flood"]:
        _flood(int(sys.argv[2]), float(sys.argv[3]))
    else:
        print(run())
