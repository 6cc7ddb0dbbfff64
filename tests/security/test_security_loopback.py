"""The default is safe: `diffctl launch sim_control` listens on loopback only, joins no multicast group, is
unreachable from another host, and its visualizer publishes nothing for a page without the token."""

from __future__ import annotations

import json
import os
import re
import sys
import threading
import time
from pathlib import Path
from typing import Any

import psutil
import pytest
from websockets.sync.client import connect

from tests.conftest import Procs, free_port
from tests.probe import Probe
from tests.security.conftest import Running
from tests.security.launch_tree import LOOPBACK, labels, listening_sockets, tree
from tests.security.netns import HostPair

HERE = Path(__file__).resolve().parent
URL_RE = r"open http://([^\s/:]+|\[[^\]]+\]):(\d+)/\?token=(\S+)"
CMD_VEL = "/diffbot_base_controller/cmd_vel"
PROBE_TOPIC = "/security_probe/cmd"
# The processes of sim_control that stay up (spawners and `create` exit once done; the controller manager
# lives inside the simulator).
RESIDENT = (
    "diffctl robot-state-publisher",
    "diffctl sim run",
    "diffctl bridge",
    "diffctl viz",
)
SCOUTING_GROUP_HEX = "E00000E0"  # 224.0.0.224, Zenoh's multicast scouting group, as /proc/net/igmp spells it


class Recorder:
    def __init__(self, node: Probe, topic: str, type_name: str) -> None:
        self.msgs: list[Any] = []
        self._lock = threading.Lock()
        node.create_subscription(topic, type_name, self._on)

    def _on(self, msg: Any) -> None:
        with self._lock:
            self.msgs.append(msg)

    def snapshot(self) -> list[Any]:
        with self._lock:
            return list(self.msgs)


def recv_until(ws: Any, kind: str, timeout_s: float = 10.0) -> dict[str, Any]:
    deadline = time.monotonic() + timeout_s
    while (left := deadline - time.monotonic()) > 0:
        msg = json.loads(ws.recv(timeout=left))
        if msg.get("type") == kind:
            return msg
    raise AssertionError(f"no {kind!r} message from the visualizer within {timeout_s} s")


def start_sim_control(procs: Procs, log_dir: Path, *launch_args: str, on: HostPair | None = None) -> Running:
    """sim_control as a user starts it; `on` runs it on host A of a namespace pair instead of here."""
    cmd = [
        sys.executable,
        "-m",
        "diffctl",
        "launch",
        "sim_control",
        *launch_args,
        "--log-dir",
        str(log_dir),
        "--no-color",
    ]
    if on is None:
        return Running(procs.start(cmd))
    env = {k: v for k, v in os.environ.items() if k != "DIFFCTL_ROUTER"}  # the default port, 7447
    return Running(procs.start(on.a.argv(*cmd), env=env))


def assert_loopback_only(launcher_pid: int) -> list[Any]:
    procs = tree(launcher_pid)
    running = labels(procs)
    for name in RESIDENT:
        assert any(label.startswith(name) for label in running), f"{name} is not running: {running}"
    sockets = listening_sockets(procs)
    exposed = [str(s) for s in sockets if s.address not in LOOPBACK]
    assert not exposed, "reachable beyond loopback:\n" + "\n".join(exposed)
    assert not [s for s in sockets if s.proto == "udp"], "UDP sockets (scouting?): " + ", ".join(map(str, sockets))
    return sockets


def stop_and_reap(procs: Procs, launch: Running) -> None:
    members = tree(launch.proc.pid)
    procs.stop(launch.proc)
    _, alive = psutil.wait_procs(members, timeout=10)
    assert not alive, f"left running: {alive}"


@pytest.mark.slow
def test_sim_control_listens_on_loopback_only_and_viz_needs_the_token(
    procs: Procs, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from diffctl.bus.session import close_session

    router_port = free_port()
    monkeypatch.setenv("DIFFCTL_ROUTER", f"tcp/127.0.0.1:{router_port}")
    launch = start_sim_control(procs, tmp_path / "log", "viz_port:=0")
    try:
        host, viz_port, token = launch.wait_for(URL_RE, timeout_s=120).groups()
        assert host in ("127.0.0.1", "localhost", "[::1]")
        sockets = assert_loopback_only(launch.proc.pid)
        by_port = {s.port: s.process for s in sockets if s.proto == "tcp"}
        assert by_port.get(router_port, "").startswith("diffctl launch"), f"no embedded router in {sockets}"
        assert by_port.get(int(viz_port), "").startswith("diffctl viz"), f"no visualizer in {sockets}"

        node = Probe("security_probe")
        cmds = Recorder(node, CMD_VEL, "geometry_msgs/msg/TwistStamped")
        probes = Recorder(node, PROBE_TOPIC, "geometry_msgs/msg/Twist")
        ws_url = f"ws://127.0.0.1:{viz_port}/ws"
        publish = {
            "op": "publish",
            "id": "p",
            "topic": PROBE_TOPIC,
            "type": "geometry_msgs/msg/Twist",
            "body": "linear: {x: 0.25}",
            "rate": 0,
        }
        # No token, then a wrong one (in the URL and by the page's auth message): watched, never obeyed.
        for url in (ws_url, f"{ws_url}?token=wrong-{token[:4]}"):
            with connect(url, open_timeout=10) as ws:
                assert recv_until(ws, "hello")["authorized"] is False
                ws.send(json.dumps({"op": "auth", "token": token[:-1]}))
                assert recv_until(ws, "auth")["authorized"] is False
                for _ in range(5):
                    ws.send(json.dumps({"op": "teleop", "linear": 0.5, "angular": 0.2}))
                    assert recv_until(ws, "refused")["op"] == "teleop"
                ws.send(json.dumps(publish))
                assert "token" in recv_until(ws, "refused")["text"]
        time.sleep(1.5)  # well past any delivery delay on loopback
        assert cmds.snapshot() == [] and probes.snapshot() == [], "a page without the token moved something"

        # The same commands with the token do reach the bus: the recorders above would have seen them.
        with connect(f"{ws_url}?token={token}", open_timeout=10) as ws:
            assert recv_until(ws, "hello")["authorized"] is True
            ws.send(json.dumps(publish))
            recv_until(ws, "publish_state")
            deadline = time.monotonic() + 10
            while not cmds.snapshot() and time.monotonic() < deadline:
                ws.send(json.dumps({"op": "teleop", "linear": 0.3, "angular": 0.0}))
                time.sleep(0.1)
            ws.send(json.dumps({"op": "teleop", "linear": 0.0, "angular": 0.0}))
        time.sleep(0.3)
        assert any(m.twist.linear.x == 0.3 for m in cmds.snapshot()), "teleop with the token published nothing"
        assert [m.linear.x for m in probes.snapshot()] == [0.25]
        node.close()
        close_session()
        stop_and_reap(procs, launch)
    except BaseException:
        print(launch.output()[-6000:])
        raise


def netns_probe(hosts: HostPair, ports: list[int]) -> dict[int, str]:
    r = hosts.b.run(sys.executable, str(HERE / "probe_connect.py"), hosts.a.address, *map(str, ports))
    assert r.returncode == 0, r.stderr
    return {int(k): v for k, v in json.loads(r.stdout).items()}


@pytest.mark.slow
def test_sim_control_is_unreachable_from_another_host(hosts: HostPair, procs: Procs, tmp_path: Path) -> None:
    # sim_control on host A exactly as a user starts it (default router port 7447, visualizer on 8080).
    launch = start_sim_control(procs, tmp_path / "log", on=hosts)
    control = Running(
        procs.start(
            hosts.a.argv(
                sys.executable,
                "-c",
                "import socket, time\n"
                "s = socket.socket(); s.bind(('0.0.0.0', 7999)); s.listen()\n"
                "print('listening', flush=True); time.sleep(300)",
            )
        )
    )
    try:
        _, viz_port, _ = launch.wait_for(URL_RE, timeout_s=120).groups()
        control.wait_for("listening")
        sockets = assert_loopback_only(launch.proc.pid)
        ports = sorted({s.port for s in sockets})
        assert 7447 in ports and int(viz_port) in ports

        # From host B, every port any process of the launch listens on (router, visualizer, each peer's own
        # listener) is refused at host A's address; the control listener proves the path works.
        seen = netns_probe(hosts, [*ports, 7999])
        assert seen.pop(7999) == "connected", "host B cannot reach host A at all: the test proves nothing"
        assert set(seen.values()) == {"refused"}, seen

        igmp = hosts.a.run("cat", "/proc/net/igmp").stdout
        assert SCOUTING_GROUP_HEX not in igmp.upper(), f"joined Zenoh's scouting group:\n{igmp}"
        assert re.search(r"010000E0", igmp), f"unexpected /proc/net/igmp (all-hosts group missing):\n{igmp}"
        stop_and_reap(procs, launch)
    except BaseException:
        print(launch.output()[-6000:])
        raise
