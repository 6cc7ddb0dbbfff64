"""The round trip a user makes: `diffctl launch sim_control record:=true`, drive a few seconds, Ctrl-C; the
bag holds every odometry message the controller published while recording (by its sequence numbers), the
independent mcap reader decodes it, and `bag play --clock` on a fresh bus gives odometry `topic echo` decodes.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory

from diffctl.bag.reader import Bag
from diffctl.interfaces import types
from tests.bag.test_files import topic_counts
from tests.conftest import free_port, wait_port
from tests.e2e.stack import Stack
from tests.waiting import wait_for

pytestmark = pytest.mark.slow
SEC = 1_000_000_000
ODOM = "/diffbot_base_controller/odom"
CMD = "/diffbot_base_controller/cmd_vel"


@pytest.fixture
def endpoint(monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    from diffctl.bus.session import close_session

    ep = f"tcp/127.0.0.1:{free_port()}"
    monkeypatch.setenv("DIFFCTL_ROUTER", ep)
    yield ep
    close_session()


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "diffctl", *args], capture_output=True, text=True, timeout=120)


def test_record_a_live_run_then_replay_it(endpoint: str, procs: Any,
                                          tmp_path: Path) -> None:
    logs = tmp_path / "logs"
    logs.mkdir()
    # A launched recorder puts its bag next to the run's logs (the launcher exports DIFFCTL_LOG_DIR).
    stack = Stack("sim_control", logs, "record:=true", rtf="1")
    try:
        node = stack.connect()
        stack.watch_odom(ODOM)
        stack.wait_controllers_active(("diffbot_base_controller", "joint_state_broadcaster"))
        assert wait_for(lambda: any(e.node_fqn == "/rosbag2_recorder" for e in node.graph.subscribers(ODOM)), 60)
        stack.command(CMD, "geometry_msgs/msg/TwistStamped", {"twist": {"linear": {"x": 0.4}, "angular": {"z": 0.3}}})
        stack.wait_sim(stack.clock_ns + 3 * SEC)
        stack.command(CMD, "geometry_msgs/msg/TwistStamped", None)
        with stack.watch.lock:
            seen_x = {s.t_ns: s.value[0] for s in stack.watch.odom}
        assert stack.stop(signal.SIGINT) == 0, stack.output()
    finally:
        stack.kill()
    assert "Recording stopped" in stack.log_path.read_text()
    [bag] = [p for p in logs.rglob("rosbag2_*") if p.is_dir()]

    info = run("bag", "info", str(bag))
    assert info.returncode == 0, info.stderr
    counts = topic_counts(info.stdout)
    for topic in ("/clock", "/joint_states", "/tf", "/tf_static", "/robot_description", "/scan"):
        assert counts.get(topic, 0) > 0, counts
    assert not any(t.startswith("/camera/") for t in counts)

    with open(bag / f"{bag.name}_0.mcap", "rb") as f:  # the independent reader and decoder
        decoded = [(m.sequence, d) for _, _, m, d in
                   make_reader(f, decoder_factories=[DecoderFactory()]).iter_decoded_messages(topics=[ODOM])]
    seqs = [s for s, _ in decoded]
    # One publisher (the controller): bag info counts exactly the messages in the bag, in publish order, never
    # doubled; their sequence numbers say how many were published meanwhile. On a sane machine that is all of
    # them; one overloaded far past its cores lets Zenoh's drop congestion control (rmw_zenoh's default as
    # well) discard a few in transit, so a small shortfall is allowed — the count still matches the bag.
    published = max(seqs) - min(seqs) + 1
    assert counts[ODOM] == len(seqs) and seqs == sorted(set(seqs))
    assert len(seqs) >= published * 19 // 20, (len(seqs), published)
    matched = [(d.pose.pose.position.x, seen_x[types.time_ns(d.header.stamp)]) for _, d in decoded
               if types.time_ns(d.header.stamp) in seen_x]
    assert len(matched) > len(decoded) // 2 and all(a == b for a, b in matched)
    recorded_x = {d.pose.pose.position.x for _, d in decoded}
    assert max(recorded_x) > 0.3  # it drove

    # Replay on a fresh bus: odometry as topic echo decodes it, and /clock from the bag's time.
    procs.diffctl("router", "--listen", endpoint)
    wait_port(int(endpoint.rsplit(":", 1)[1]), 30)
    env = {**os.environ, "COLUMNS": "200"}
    echo = procs.diffctl("topic", "echo", ODOM, "nav_msgs/msg/Odometry", "--once", stderr=subprocess.DEVNULL, env=env)
    clock = procs.diffctl("topic", "echo", "/clock", "rosgraph_msgs/msg/Clock", "--once",
                          stderr=subprocess.DEVNULL, env=env)
    player = procs.diffctl("bag", "play", str(bag), "--clock", "--loop", "--topics", ODOM)
    odom_doc = yaml.safe_load(echo.communicate(timeout=120)[0].split("---")[0])
    clock_doc = yaml.safe_load(clock.communicate(timeout=120)[0].split("---")[0])
    procs.stop(player)
    assert odom_doc["pose"]["pose"]["position"]["x"] in recorded_x
    b = Bag(bag)
    start, end = b.metadata.starting_time_ns, b.metadata.end_ns
    b.close()
    played_clock = clock_doc["clock"]["sec"] * SEC + clock_doc["clock"]["nanosec"]
    assert start - SEC <= played_clock <= end + SEC  # bag time (the recorder's receive time), as rosbag2
