"""Garbage on the wire: malformed, truncated, wrong-type, empty, attachment-less and oversized payloads published
raw (zenoh, rmw_zenoh keys and attachment) on every topic the nodes of a running sim_control subscribe to, found
from the graph, plus the simulator-side keys (bridged gz topics) and every
service. Each is dropped with a rate-limited warning; every node keeps running and keeps doing its job.
"""

from __future__ import annotations

import contextlib
import itertools
import math
import os
import re
import signal
import threading
import time
import urllib.request
from collections import Counter
from pathlib import Path

import pytest
from websockets.sync.client import connect as ws_connect

from diffctl.bus import gz, wire
from diffctl.bus.session import domain_id
from diffctl.interfaces import types
from tests.conftest import free_port
from tests.reliability.stack_faults import (
    CMD,
    CONTROLLERS,
    ODOM,
    SEC,
    TWIST_STAMPED,
    drive,
    launch_log,
    moved_m,
    pids,
    start_stack,
    wait_until,
)

pytestmark = pytest.mark.slow
REPEAT = 25  # of each kind on each key: far more than one warning period lets through
OVERSIZED = 4 * 1024 * 1024
CDR_HEADER = b"\x00\x01\x00\x00"


def _page_answers(port: int) -> bool:
    try:
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=1) as r:
            return r.status == 200
    except OSError:
        return False


def payloads(typename: str | None, oversized: bytes = b"") -> dict[str, bytes]:
    rnd = os.urandom
    out = {
        "empty": b"",
        "random": rnd(37),
        "header+junk": CDR_HEADER + b"\xff" * 29,
        "huge length prefix": CDR_HEADER + b"\xff\xff\xff\x7f" * 8,
        "oversized": oversized or CDR_HEADER + rnd(OVERSIZED),
        "wrong type": types.serialize(types.new("sensor_msgs/msg/Imu", {}), "sensor_msgs/msg/Imu"),
    }
    if typename is not None:
        valid = types.serialize(types.new(typename, {}), typename)
        out["truncated"] = valid[: max(4, len(valid) // 2)]
        out["cut header"] = valid[:3]
    return out


def _read_all(page) -> None:
    with contextlib.suppress(Exception):
        for _ in page:
            pass


def test_garbage_on_every_subscribed_topic_is_dropped_and_every_node_keeps_working(
    stack_env: str, tmp_path: Path
) -> None:
    viz_port = free_port()
    stack = start_stack(tmp_path, "viz:=true", f"viz_port:={viz_port}")
    with contextlib.ExitStack() as cleanup:
        cleanup.callback(stack.kill)
        w = stack.watch
        wait_until(lambda: "rviz2" in pids(stack), 30, "the visualizer started", stack)
        node = stack.node
        assert node is not None
        # The visualizer takes the streams it draws while a page is open: open one for the whole test.
        wait_until(lambda: _page_answers(viz_port), 30, "the visualizer's page answers", stack)
        page = cleanup.enter_context(ws_connect(f"ws://127.0.0.1:{viz_port}/ws", open_timeout=10, ping_interval=None))
        # It reads what it is sent, as a browser's page does: a page that stops reading fills the socket, and then
        # neither the visualizer's stop nor this end's close completes before its timeout.
        threading.Thread(target=_read_all, args=(page,), daemon=True).start()
        # Every (topic, type) some process of the launch subscribes to, from the graph.
        wait_until(
            lambda: any(e.node == "rviz2" for e in node.graph.subscribers("/tf")),
            30,
            "the visualizer's subscriptions in the graph",
            stack,
        )
        time.sleep(1.0)
        targets = sorted(
            {(t, e.type) for t in node.graph.topics() for e in node.graph.subscribers(t) if e.node != "e2e_test"}
        )
        topics = {t for t, _ in targets}
        for expected in ("/diffbot_base_controller/cmd_vel", "/joint_states", "/robot_description", "/clock", "/tf"):
            assert expected in topics, f"{expected} not among the subscribed topics {sorted(topics)}"
        services = sorted((s, ts[0]) for s, ts in node.graph.services().items() if ts)
        assert any(s == "/controller_manager/list_controllers" for s, _ in services), services
        before = pids(stack)

        drive(stack, 0.3, 0.0, 3, 0.3)
        session = node.session
        t_inject = time.monotonic()
        gid = os.urandom(16)
        sent = Counter()
        domain = domain_id()
        oversized = CDR_HEADER + os.urandom(OVERSIZED)  # one buffer for every key: making it is not the test
        garbage = {ty: payloads(ty, oversized) for ty in {ty for _, ty in targets} | {None}}
        for seq in range(REPEAT):
            for topic, typename in targets:
                key = wire.topic_key(domain, topic, typename)
                for kind, data in garbage[typename].items():
                    if kind == "oversized" and seq > 1:
                        continue  # two of 4 MB per topic are enough to show it
                    att = None if kind == "empty" and seq % 2 else wire.pack_attachment(seq, time.time_ns(), gid)
                    session.put(key, data, attachment=att)
                    sent["topic"] += 1
            # Simulator side: the keys the bridge takes gz data from.
            for key in (gz.key("/clock"), gz.key("/lidar"), gz.key("/imu")):
                for kind, data in garbage[None].items():
                    if kind != "oversized" or seq < 2:
                        session.put(key, data)
                        sent["gz"] += 1
        # Each service's requests go at once and their answers (or the timeout) are awaited together.
        for service, srv_type in services:
            key = wire.service_key(domain, service, srv_type)
            answers = [
                session.get(key, payload=data, attachment=wire.pack_attachment(1, time.time_ns(), gid), timeout=2.0)
                for data in garbage[None].values()
            ]
            for answer in answers:
                for _ in answer:
                    pass
                sent["service"] += 1
        assert sent["topic"] > 1000, sent
        inject_s = time.monotonic() - t_inject

        # Everything still runs and works: same processes, the car drives, topics flow, services answer.
        time.sleep(1.0)
        log = launch_log(stack)
        assert "Traceback" not in log, log[-4000:]
        assert not re.search(r"process has died", log), log[-4000:]
        assert pids(stack) == before
        assert stack.proc.poll() is None
        drive(stack, -0.2, 0.3, 4, 0.3)
        t = stack.clock_ns
        stack.wait_sim(t + 3 * SEC)
        time.sleep(0.5)  # bridged samples trail the controller's
        # In sim time: 20–50 Hz topics, and /clock, which at rtf 0 is thinned to ≤ 250 Hz of wall time (a few Hz
        # of sim time at this machine's real-time factor), so for it "flowing" is a lower bar.
        for topic, min_hz in ((ODOM, 15), ("/joint_states", 15), ("/tf", 15), ("/clock", 2)):
            with w.lock:
                last = sorted(w.stamps.get(topic, []))[-3:]
            rate = w.rate_hz(topic, t, t + 2 * SEC)
            assert rate > min_hz, f"{topic} stopped flowing after the garbage: {rate:.1f} Hz, {last}, {t}"
        states = stack.controllers()
        assert all(states.get(c) == "active" for c in CONTROLLERS), states
        with urllib.request.urlopen(f"http://127.0.0.1:{viz_port}/", timeout=5) as r:
            assert r.status == 200

        # Dropped with a warning, rate-limited: a handful of lines per process and topic, not one per sample.
        dropped = [ln for ln in log.splitlines() if "dropped" in ln]
        assert any("/diffbot_base_controller/cmd_vel" in ln for ln in dropped), "\n".join(dropped[:20])
        # One warning per (node, what, topic) per 5 s throttle period, the rest counted as "N more suppressed".
        per_key = Counter(m[1] + m[2] for ln in dropped if (m := re.search(r"(\[[\w.-]+\]): (.*?dropped [^:(]*)", ln)))
        assert len(per_key) >= 20, per_key  # every node on every topic it subscribes to said so
        worst = per_key.most_common(1)[0]
        assert worst[1] <= inject_s / 5 + 2, f"not rate-limited: {worst} in {inject_s:.1f} s of injection"
        # The count of suppressed lines rides on the next warning after the 5 s throttle period. The injection may
        # end within one period for every key (how long it takes depends on how many services answer at once), so
        # garbage keeps coming on one topic, a sample a second, until a warning counts the suppressed ones: the
        # period runs from that subscriber's first warning, which a busy process may log well after the injection.
        (cmd_key,) = {wire.topic_key(domain, t, ty) for t, ty in targets if t == "/diffbot_base_controller/cmd_vel"}
        deadline = time.monotonic() + 30.0
        while "more suppressed" not in launch_log(stack):
            assert time.monotonic() < deadline, "no warning counted the suppressed ones: " + launch_log(stack)[-3000:]
            session.put(cmd_key, garbage[None]["random"], attachment=wire.pack_attachment(REPEAT, time.time_ns(), gid))
            time.sleep(1.0)

        # Well-formed but absurd commands (NaN, ±inf, 1e308) never reach the physics: the controller's limits and
        # finiteness checks hold the car to |v| ≤ 1 m/s and |ω| ≤ 1 rad/s (the tutorial's limits), all finite.
        for v in (math.nan, math.inf, -math.inf, 1e308, -1e308):
            stack.command(CMD, TWIST_STAMPED, {"twist": {"linear": {"x": v}, "angular": {"z": v}}})
            stack.wait_sim(stack.clock_ns + SEC // 2)
        stack.command(CMD, TWIST_STAMPED, None)
        stack.wait_sim(stack.clock_ns + SEC)
        with w.lock:
            odom = [s.value for s in w.odom if s.t_ns > t]
            truth_samples = [s for s in w.truth if s.t_ns > t]
        truth = [s.value for s in truth_samples]
        assert odom and truth
        assert all(math.isfinite(x) for sample in odom + truth for x in sample), "non-finite odometry or pose"
        assert max(abs(o[3]) for o in odom) <= 1.0 + 1e-6 and max(abs(o[4]) for o in odom) <= 1.0 + 1e-6
        # Never faster than the limits allow (with slack for the wheels' slip): a jump would show as a huge speed
        # between two poses, however many samples this busy process missed between them.
        speeds = [
            moved_m(a.value, b.value) / ((b.t_ns - a.t_ns) / SEC)
            for a, b in itertools.pairwise(truth_samples)
            if b.t_ns > a.t_ns
        ]
        assert max(speeds) < 1.5, f"the car jumped: {max(speeds):.2f} m/s between two poses"

        assert stack.stop(signal.SIGINT) == 0, stack.output()
        assert not stack.survivors()
