"""Recording and replaying over a real router: late and latched topics, sequence numbers kept, Ctrl-C and
SIGKILL, remapped replay, a type diffctl never knew replayed from the bag's own schema, bad bags silent."""

from __future__ import annotations

import signal
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import pytest
from mcap.reader import make_reader
from mcap.records import Message as McapMessage
from mcap.stream_reader import StreamReader

from diffctl.bag.msgdefs import register_schema
from diffctl.bag.reader import Bag
from diffctl.interfaces import types
from tests.bag.fixtures import BASIC, rosbags_bag
from tests.bag.test_files import one_error_line, topic_counts, write_bag
from tests.probe import Probe
from tests.waiting import wait_for

STRING = "std_msgs/msg/String"


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "diffctl", *args], capture_output=True, text=True, timeout=120)


def complete_messages(path: Path) -> int:
    """Messages in the complete records of a file still being written, read by the mcap library."""
    n = 0
    try:
        with open(path, "rb") as f:
            for rec in StreamReader(f).records:
                n += isinstance(rec, McapMessage)
    except Exception:  # the first incomplete record ends the count
        pass
    return n


def settled_count(path: Path, quiet_s: float = 3.0, timeout_s: float = 90.0) -> int:
    """complete_messages once it has stopped growing for `quiet_s` (the recorder flushes every second)."""
    deadline = time.monotonic() + timeout_s
    last, since = -1, time.monotonic()
    while time.monotonic() < deadline:
        n = complete_messages(path)
        if n != last:
            last, since = n, time.monotonic()
        elif n > 0 and time.monotonic() - since >= quiet_s:
            return n
        time.sleep(0.2)
    raise AssertionError(f"{path} never settled (last count {last})")


def recorder_subscribed(node: Probe, topic: str) -> bool:
    return any(e.node_fqn == "/rosbag2_recorder" for e in node.graph.subscribers(topic))


def test_record_late_and_latched_topics_then_ctrl_c(router: str, procs: Any, tmp_path: Path) -> None:
    node = Probe("bag_test_pub")
    latched = node.create_publisher("/robot_description", STRING, latched=True)
    latched.publish({"data": "<robot name='r'/>"})
    chatter = node.create_publisher("/chatter", STRING)
    bag = tmp_path / "run"
    rec = procs.diffctl("bag", "record", "-a", "-o", str(bag))
    # The graph shows the recorder's subscription; Zenoh's matching status says its route reached us.
    assert wait_for(lambda: recorder_subscribed(node, "/chatter") and recorder_subscribed(node, "/robot_description")
                    and chatter.matching, 60), rec.stdout
    for i in range(40):
        chatter.publish({"data": f"m{i}"})
        time.sleep(0.02)
    late = node.create_publisher("/late", "geometry_msgs/msg/Twist")  # appears after the recording started
    assert wait_for(lambda: recorder_subscribed(node, "/late") and late.matching, 30)
    for i in range(7):
        late.publish({"linear": {"x": float(i)}})
    time.sleep(1.0)
    assert procs.stop(rec, signal.SIGINT, 30) == 0
    out = rec.stdout.read()
    assert "[rosbag2_recorder]: Recording stopped" in out
    info = run("bag", "info", str(bag))
    assert info.returncode == 0, info.stderr
    counts = topic_counts(info.stdout)
    assert counts["/robot_description"] == 1
    with open(bag / "run_0.mcap", "rb") as f:
        recorded = [(ch.topic, m.sequence) for _, ch, m in make_reader(f).iter_messages()]
        seqs = {t: [seq for topic, seq in recorded if topic == t] for t in ("/chatter", "/late")}
        f.seek(0)
        qos = {ch.topic: ch.metadata["offered_qos_profiles"] for ch in make_reader(f).get_summary().channels.values()}
    # The MCAP keeps the publishers' own sequence numbers, and bag info counts exactly what was recorded.
    # On a sane machine that is every message; one overloaded far past its cores lets Zenoh's drop congestion
    # control (rmw_zenoh's default too) discard a few in transit — never doubled, never reordered.
    for topic, published in (("/chatter", 40), ("/late", 7)):
        got = seqs[topic]
        assert counts[topic] == len(got) and got == sorted(set(got)) and set(got) <= set(range(1, published + 1))
        assert len(got) >= published * 9 // 10, (topic, got)
    assert "transient_local" in qos["/robot_description"] and "volatile" in qos["/chatter"]
    node.close()


def test_killed_recorder_is_recovered_by_reindex(router: str, procs: Any, tmp_path: Path) -> None:
    node = Probe("bag_test_kill")
    pub = node.create_publisher("/chatter", STRING)
    bag = tmp_path / "killed"
    rec = procs.diffctl("bag", "record", "/chatter", "-o", str(bag))
    assert wait_for(lambda: recorder_subscribed(node, "/chatter") and pub.matching, 60)
    for i in range(30):
        pub.publish({"data": f"m{i}"})
        time.sleep(0.02)
    # The recorder hands complete chunks to the OS every second: wait until what it received is on disk.
    on_disk = settled_count(bag / "killed_0.mcap")
    assert on_disk >= 27
    procs.stop(rec, signal.SIGKILL)
    assert "reindex" in one_error_line(run("bag", "info", str(bag)))
    assert run("bag", "reindex", str(bag)).returncode == 0
    info = run("bag", "info", str(bag))
    assert info.returncode == 0 and topic_counts(info.stdout) == {"/chatter": on_disk}
    node.close()


def test_play_remapped_with_clock(router: str, tmp_path: Path) -> None:
    bag = tmp_path / "odom"
    write_bag(bag, n=25)
    node = Probe("bag_test_sub")
    got: list[float] = []
    clocks: list[int] = []
    node.create_subscription("/replayed", "nav_msgs/msg/Odometry", lambda m: got.append(m.pose.pose.position.x))
    node.create_subscription("/clock", "rosgraph_msgs/msg/Clock", lambda m: clocks.append(types.time_ns(m.clock)))
    out = run("bag", "play", str(bag), "--remap", "/odom:=/replayed", "--clock", "100", "--rate", "0.25")
    assert out.returncode == 0, out.stderr
    assert wait_for(lambda: len(got) == 25, 60)
    assert got == [0.25 * i for i in range(25)]
    assert clocks and all(1_700_000_000 * 10**9 <= c <= 1_700_000_000 * 10**9 + 10**9 for c in clocks)
    node.close()


def test_a_type_unknown_here_plays_from_its_schema(router: str, tmp_path: Path) -> None:
    bag = tmp_path / "basic"
    rosbags_bag(bag, version=8)
    b = Bag(bag)
    ch = b.channels()["/basic"]
    b.close()
    register_schema(ch.type, ch.schema_encoding, ch.schema_text, "test")  # as a decoding client learns it
    node = Probe("bag_test_basic")
    got: list[Any] = []
    node.create_subscription("/basic", BASIC, got.append)
    out = run("bag", "play", str(bag), "--topics", "/basic", "--rate", "4")
    assert out.returncode == 0, out.stderr
    assert wait_for(lambda: len(got) == 5, 10)
    assert [m.int32_value for m in got] == [-32 * i for i in (0, 4, 8, 12, 16)]
    assert got[0].uint64_value == 2**50 and got[0].bool_value is True
    node.close()


def test_a_bad_bag_publishes_nothing(router: str, tmp_path: Path) -> None:
    bag = tmp_path / "cut"
    write_bag(bag, n=300)
    f = bag / "cut_0.mcap"
    f.write_bytes(f.read_bytes()[: f.stat().st_size - 100])
    node = Probe("bag_test_bad")
    got = threading.Event()
    node.create_subscription("/odom", "nav_msgs/msg/Odometry", lambda m: got.set())
    one_error_line(run("bag", "play", str(bag)))
    assert not got.wait(1.0)
    assert not any(e.node_fqn == "/rosbag2_player" for e in node.graph.entities())
    node.close()


@pytest.mark.parametrize("args", [["--rate", "0"], ["--remap", "nocolon"], ["--topics", "/nope"]])
def test_bad_play_arguments(tmp_path: Path, args: list[str]) -> None:
    bag = tmp_path / "b"
    write_bag(bag, n=3)
    one_error_line(run("bag", "play", str(bag), *args))


def test_keyboard_pause_step_resume_in_a_terminal(router: str, procs: Any, tmp_path: Path) -> None:
    import os
    import pty

    bag = tmp_path / "keys"
    write_bag(bag, n=25)
    node = Probe("bag_test_keys")
    got: list[float] = []
    node.create_subscription("/odom", "nav_msgs/msg/Odometry", lambda m: got.append(m.pose.pose.position.x))
    master, slave = pty.openpty()
    player = procs.diffctl("bag", "play", str(bag), "--start-paused", stdin=slave)
    try:
        assert wait_for(lambda: any(e.node_fqn == "/rosbag2_player" for e in node.graph.publishers("/odom")), 60)
        time.sleep(1.0)
        assert got == []  # paused from the start
        os.write(master, b"\x1b[C")  # → publishes exactly the next message
        assert wait_for(lambda: len(got) == 1, 20)
        time.sleep(0.5)
        assert got == [0.0]
        os.write(master, b" ")  # SPACE resumes
        assert wait_for(lambda: len(got) == 25, 20)
        assert player.wait(30) == 0
        assert "[rosbag2_player]: Resuming play." in player.stdout.read()
    finally:
        os.close(master)
        os.close(slave)
        node.close()
