"""The bus with real sessions and processes on loopback: pub/sub, latching, services, graph, CLI tools."""

from __future__ import annotations

import os
import select
import subprocess
import sys
import textwrap
import threading
import time

import psutil
import pytest

from diffctl.errors import BusError, ServiceTimeout
from diffctl.interfaces import types
from tests.probe import Probe


def wait_for(pred, timeout_s: float = 5.0, step_s: float = 0.02) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if pred():
            return True
        time.sleep(step_s)
    return pred()


def python_child(procs, code: str):
    return procs.start([sys.executable, "-c", textwrap.dedent(code)])


def test_pub_sub_and_latched_late_joiner(router: str) -> None:
    a, b = Probe("talker"), Probe("listener")
    got: list = []
    b.create_subscription("/cmd_vel", "geometry_msgs/msg/TwistStamped", got.append)
    pub = a.create_publisher("/cmd_vel", "geometry_msgs/msg/TwistStamped")
    assert wait_for(lambda: pub.subscription_count == 1)
    pub.publish({"twist": {"linear": {"x": 0.5}}})
    assert wait_for(lambda: got)
    assert got[0].twist.linear.x == 0.5

    latched = a.create_publisher("/robot_description", "std_msgs/msg/String", latched=True)
    latched.publish({"data": "<sdf version='1.8'/>"})
    time.sleep(0.1)
    late: list = []
    b.create_subscription("/robot_description", "std_msgs/msg/String", late.append, latched=True)
    assert wait_for(lambda: late), "a late subscriber must get the latched sample"
    assert late[0].data == "<sdf version='1.8'/>"


def test_services_answer_fail_and_time_out(router: str) -> None:
    server, caller = Probe("server"), Probe("caller")
    release = threading.Event()

    def handler(req):
        if req.data:
            raise RuntimeError("refused on purpose")
        return types.response("std_srvs/srv/SetBool", {"success": True, "message": "ok"})

    server.create_service("~/set", "std_srvs/srv/SetBool", handler)
    server.create_service("~/slow", "std_srvs/srv/Trigger", lambda _r: release.wait(5) and {"success": True})
    cli = caller.create_client("/server/set", "std_srvs/srv/SetBool")
    assert cli.wait_for_service(5)
    assert cli.call({"data": False}).success is True
    with pytest.raises(BusError, match="refused on purpose"):
        cli.call({"data": True})
    slow = caller.create_client("/server/slow", "std_srvs/srv/Trigger")
    assert slow.wait_for_service(5)
    t0 = time.monotonic()
    with pytest.raises(ServiceTimeout):
        slow.call({}, timeout=0.5)
    assert time.monotonic() - t0 < 2.0
    release.set()
    missing = caller.create_client("/nobody/home", "std_srvs/srv/Trigger")
    assert not missing.wait_for_service(0.2)
    with pytest.raises(BusError, match="no server"):
        missing.call({}, timeout=2.0)


def test_a_client_waiting_for_its_service_wakes_when_the_server_appears(router: str) -> None:
    """wait_for_service waits on graph changes (no polling): a server that comes later is found, one that never
    comes is not, and a wait without limit ends as soon as the server is there."""
    caller = Probe("waiter")
    cli = caller.create_client("/late/trigger", "std_srvs/srv/Trigger")
    assert not cli.wait_for_service(0.1)
    found: list[bool] = []
    waiter = threading.Thread(target=lambda: found.append(cli.wait_for_service(None)))
    waiter.start()
    time.sleep(0.2)
    assert not found
    late = Probe("late")
    late.create_service("~/trigger", "std_srvs/srv/Trigger", lambda _r: {"success": True})
    waiter.join(10)
    assert found == [True]
    assert cli.call({}).success is True
    late.close()
    assert caller.graph.wait_for(lambda: not cli.service_is_ready(), 10)
    caller.close()


def test_graph_lists_what_exists_and_forgets_what_died(router: str, procs) -> None:
    child = python_child(
        procs,
        """
        from tests.probe import Probe
        n = Probe("ghost", "/robot1")
        n.create_publisher("/ghost_topic", "std_msgs/msg/String")
        n.create_service("~/ping", "std_srvs/srv/Trigger", lambda r: {"success": True})
        print("ready", flush=True)
        n.spin()
    """,
    )
    assert child.stdout.readline().strip() == "ready"
    me = Probe("observer")
    g = me.graph
    assert wait_for(lambda: "/robot1/ghost" in g.nodes())
    assert wait_for(lambda: g.topics().get("/ghost_topic") == ["std_msgs/msg/String"])
    assert "/robot1/ghost/ping" in g.services()
    child.kill()  # SIGKILL: no chance to undeclare anything
    assert wait_for(lambda: "/robot1/ghost" not in g.nodes(), timeout_s=5)
    assert "/ghost_topic" not in g.topics()


def read_until(proc: subprocess.Popen, text: str, seen: list[str], timeout_s: float = 30.0) -> str:
    """What `proc` has printed once `text` is in it (stdout and stderr share the pipe, so a log line from
    another thread may land inside a print: the whole is searched, not lines); `seen` keeps it all."""
    deadline = time.monotonic() + timeout_s
    fd = proc.stdout.fileno()
    while text not in "".join(seen):
        ready, _, _ = select.select([fd], [], [], max(0.0, deadline - time.monotonic()))
        chunk = os.read(fd, 65536).decode(errors="replace") if ready else ""
        if not chunk:
            raise AssertionError(f"{text!r} not printed within {timeout_s} s: {''.join(seen)!r}")
        seen.append(chunk)
    return "".join(seen)


def test_type_mismatch_is_reported_by_both_ends(router: str, procs) -> None:
    code = """
        from tests.probe import Probe
        n = Probe("{node}")
        n.{create}("/cmd_vel", "geometry_msgs/msg/{type}"{extra})
        print("ready", flush=True)
        n.spin()
    """
    sub = python_child(procs, code.format(node="controller", create="create_subscription", type="TwistStamped",
                                          extra=", print"))
    out_sub: list[str] = []
    read_until(sub, "ready", out_sub)
    pub = python_child(procs, code.format(node="teleop", create="create_publisher", type="Twist", extra=""))
    out_pub: list[str] = []
    read_until(pub, "ready", out_pub)
    g = Probe("observer").graph
    assert wait_for(lambda: len(g.topics().get("/cmd_vel", [])) == 2)
    info = subprocess.run([sys.executable, "-m", "diffctl", "topic", "info", "/cmd_vel"], capture_output=True,
                          text=True, timeout=20)
    assert info.returncode == 0
    assert "type mismatch on /cmd_vel" in info.stderr
    read_until(pub, "this node publishes geometry_msgs/msg/Twist but /controller subscribes to", out_pub)
    read_until(sub, "this node subscribes to geometry_msgs/msg/TwistStamped but /teleop publishes", out_sub)
    procs.stop(pub)
    procs.stop(sub)


def test_topic_pub_to_topic_echo_across_processes(router: str, procs) -> None:
    echo = procs.diffctl("topic", "echo", "/chatter", "std_msgs/msg/String", "--once")
    time.sleep(0.5)
    pub = subprocess.run(
        [sys.executable, "-m", "diffctl", "topic", "pub", "/chatter", "std_msgs/msg/String", "{data: hello}", "--once"],
        capture_output=True,
        text=True,
        timeout=20,
    )
    assert pub.returncode == 0, pub.stderr
    out, _ = echo.communicate(timeout=15)
    assert echo.returncode == 0
    assert "data: hello\n---" in out


def test_topic_pub_fills_zero_stamp_and_finds_topic_by_last_segment(router: str, procs) -> None:
    me = Probe("controller", "/")
    got: list = []
    me.create_subscription("/diffbot_base_controller/cmd_vel", "geometry_msgs/msg/TwistStamped", got.append)
    time.sleep(0.3)
    before = time.time_ns()
    pub = subprocess.run(
        [
            sys.executable,
            "-m",
            "diffctl",
            "topic",
            "pub",
            "cmd_vel",
            "{twist: {linear: {x: 0.5}, angular: {z: 0.3}}}",
            "--times",
            "2",
            "--rate",
            "20",
        ],
        capture_output=True,
        text=True,
        timeout=20,
    )
    assert pub.returncode == 0, pub.stderr
    assert "using topic /diffbot_base_controller/cmd_vel" in pub.stderr
    assert pub.stderr.count("filling it with the current") == 1
    assert wait_for(lambda: len(got) == 2)
    assert got[0].twist.angular.z == 0.3
    assert types.time_ns(got[0].header.stamp) >= before


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["topic", "pub", "/x", "geometry_msgs/msg/Twist", "{linaer: {x: 1}}"], "did you mean 'linear'"),
        (["topic", "pub", "/x", "geometry_msgs/msg/Twist", "{linear: {x: fast}}"], "linear.x"),
        (["topic", "pub", "/x", "geometry_msgs/msg/Twst", "{}"], "did you mean"),
        (["topic", "pub", "/x", "geometry_msgs/msg/Twist", "{linear: [}"], "not valid YAML"),
    ],
)
def test_topic_pub_bad_input_is_one_line_exit_2(router: str, argv: list[str], needle: str) -> None:
    r = subprocess.run([sys.executable, "-m", "diffctl", *argv], capture_output=True, text=True, timeout=20)
    assert r.returncode == 2
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and needle in lines[0], r.stderr
    assert "Traceback" not in r.stderr


def test_no_router_is_one_line_and_exit_2_within_2_s(monkeypatch: pytest.MonkeyPatch) -> None:
    from tests.conftest import free_port

    env = {**os.environ, "DIFFCTL_ROUTER": f"tcp/127.0.0.1:{free_port()}"}
    t0 = time.monotonic()
    r = subprocess.run(
        [sys.executable, "-m", "diffctl", "topic", "list"], capture_output=True, text=True, timeout=20, env=env
    )
    elapsed = time.monotonic() - t0
    assert r.returncode == 2
    assert r.stderr.strip().count("\n") == 0 and "no Zenoh router answers at tcp/127.0.0.1:" in r.stderr
    assert "diffctl router" in r.stderr
    # Measured for the record; the budget is 2 s on top of interpreter start-up.
    assert elapsed < 10


def test_peers_listen_on_loopback_only(router: str, procs) -> None:
    child = python_child(
        procs,
        """
        from tests.probe import Probe
        n = Probe("listener_check")
        print("ready", flush=True)
        n.spin()
    """,
    )
    assert child.stdout.readline().strip() == "ready"
    listening = [c for c in psutil.Process(child.pid).net_connections(kind="inet") if c.status == "LISTEN"]
    assert listening, "a peer listens for direct links"
    assert all(c.laddr.ip == "127.0.0.1" for c in listening), listening


def test_domain_id_separates_graphs(router: str, procs, monkeypatch: pytest.MonkeyPatch) -> None:
    env = {**os.environ, "ROS_DOMAIN_ID": "7"}
    child = procs.start(
        [
            sys.executable,
            "-c",
            textwrap.dedent("""
        from tests.probe import Probe
        n = Probe("other_domain")
        n.create_publisher("/elsewhere", "std_msgs/msg/String")
        print("ready", flush=True)
        n.spin()
    """),
        ],
        env=env,
    )
    assert child.stdout.readline().strip() == "ready"
    time.sleep(0.3)
    assert "/elsewhere" not in Probe("domain0").graph.topics()


def test_ignore_local_drops_this_process_publications(router: str, procs) -> None:
    n = Probe("bridge_like")
    heard_all: list = []
    heard_remote: list = []
    n.create_subscription("/both", "std_msgs/msg/String", heard_all.append)
    n.create_subscription("/both", "std_msgs/msg/String", heard_remote.append, ignore_local=True)
    pub = n.create_publisher("/both", "std_msgs/msg/String")
    time.sleep(0.2)
    pub.publish({"data": "mine"})
    r = subprocess.run([sys.executable, "-m", "diffctl", "topic", "pub", "/both", "std_msgs/msg/String",
                        "{data: theirs}", "--once"], capture_output=True, text=True, timeout=20)
    assert r.returncode == 0, r.stderr
    assert wait_for(lambda: len(heard_all) == 2)
    assert [m.data for m in heard_remote] == ["theirs"]
