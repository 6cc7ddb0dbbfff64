"""`diffctl viz` as a process: files over HTTP, live streams over the WebSocket, commands and their guards."""

from __future__ import annotations

import asyncio
import http.client
import json
import re
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
import websockets
from websockets.exceptions import InvalidStatus

from tests.probe import Probe
from tests.viz.recorder import Recorder

REPO = Path(__file__).resolve().parents[2]
CMD_TOPIC = "/diffbot_base_controller/cmd_vel"


def http_get(host_port: str, path: str, headers: dict[str, str] | None = None) -> tuple[int, dict[str, str], bytes]:
    conn = http.client.HTTPConnection(host_port, timeout=5)
    try:
        conn.request("GET", path, headers=headers or {})
        r = conn.getresponse()
        return r.status, {k.lower(): v for k, v in r.getheaders()}, r.read()
    finally:
        conn.close()


async def recv_until(ws, pred, timeout_s: float = 10.0) -> dict:
    deadline = time.monotonic() + timeout_s
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            raise AssertionError("expected message did not arrive")
        m = json.loads(await asyncio.wait_for(ws.recv(), left))
        if pred(m):
            return m


def odom_pose(frame: dict) -> list[float] | None:
    """[x, y, yaw] of the controller's odometry in the fixed frame, from a frame view (None: not received yet; the
    visualizer subscribes when the page opens, so its first frames may come before the first odometry)."""
    return next((o["pose"] for o in frame["odom"] if o["topic"] == "/diffbot_base_controller/odom"), None)


@pytest.mark.slow
def test_streams_follow_the_robot_and_teleop_drives_it(fake_robot, viz) -> None:
    # Static files: self-contained, with a CSP that forbids loading anything from elsewhere.
    status, headers, body = http_get(viz.host_port, "/")
    assert status == 200 and b"<canvas" in body and b"http" not in body.replace(b"http-equiv", b"")
    assert "default-src 'none'" in headers["content-security-policy"]
    assert http_get(viz.host_port, "/viz.js")[0] == 200
    assert http_get(viz.host_port, "/panels.js")[0] == 200
    assert http_get(viz.host_port, "/secret")[0] == 404
    assert http_get(viz.host_port, "/", {"Host": "evil.example:80"})[0] == 403  # DNS rebinding

    node = Probe("viz_test_listener")
    cmds = Recorder(node, CMD_TOPIC, "geometry_msgs/msg/TwistStamped")

    async def session() -> None:
        async with websockets.connect(f"{viz.ws_url}?token={viz.token}") as ws:
            hello = await recv_until(ws, lambda m: m["type"] == "hello")
            assert hello["authorized"] is True and hello["fixed_frame"] == "odom"
            assert hello["teleop"]["topic"] == CMD_TOPIC
            robot = await recv_until(ws, lambda m: m["type"] == "robot" and m["name"])
            assert {"base_link", "left_wheel", "right_wheel", "lidar_link"} <= set(robot["links"])
            frame = await recv_until(ws, lambda m: m["type"] == "frame" and m["robot"] and (odom_pose(m) or []))
            assert {"odom", "base_footprint", "base_link"} <= set(frame["frames"])
            chassis = [p for p in frame["robot"] if p["link"] == "base_link"]
            assert chassis and len(chassis[0]["pts"]) >= 8
            scan = await recv_until(ws, lambda m: m["type"] == "scan" and m["scans"].get("/scan", {}).get("pts"))
            pts = scan["scans"]["/scan"]["pts"]
            # The fake room's walls are at |x|, |y| = 3 m: every point lies on one of them, in the odom frame.
            assert len(pts) == 720
            assert all(abs(max(abs(pts[i]), abs(pts[i + 1])) - 3.0) < 0.01 for i in range(0, len(pts), 2))
            status = await recv_until(ws, lambda m: m["type"] == "status" and m["sim_time"] and m["joints"])
            assert status["joints"][0]["effort"] is None  # NaN effort arrives as null, not as invalid JSON
            graph = await recv_until(
                ws, lambda m: m["type"] == "graph" and any(t["name"] == "/scan" and t["hz"] for t in m["topics"])
            )
            scan_hz = next(t["hz"] for t in graph["topics"] if t["name"] == "/scan")
            assert 7.0 <= scan_hz <= 13.0

            x0 = odom_pose(frame)[0]
            for _ in range(10):  # hold "forward" for one second at 10 Hz, as the page does
                await ws.send(json.dumps({"op": "teleop", "linear": 0.5, "angular": 0.0}))
                await asyncio.sleep(0.1)
            moved = await recv_until(ws, lambda m: m["type"] == "frame" and (odom_pose(m) or [x0])[0] > x0 + 0.3)
            assert moved["robot"]
            # Absurd and non-finite commands: clamped or refused, never published as such.
            await ws.send(json.dumps({"op": "teleop", "linear": 1e9, "angular": -1e9}))
            await ws.send('{"op": "teleop", "linear": NaN}')
            err = await recv_until(ws, lambda m: m["type"] == "error")
            assert "finite" in err["text"]
            # Then the page goes silent without releasing: the server sends the zero itself.
            notice = await recv_until(ws, lambda m: m["type"] == "notice", timeout_s=3)
            assert "stopped" in notice["text"]

    asyncio.run(session())
    time.sleep(0.3)
    seen = cmds.snapshot()
    xs = [m.twist.linear.x for m in seen]
    assert xs.count(0.5) >= 8
    assert max(abs(x) for x in xs) == 1.0 and min(m.twist.angular.z for m in seen) == -2.0  # clamped to limits
    assert xs[-1] == 0.0 and seen[-1].twist.angular.z == 0.0
    assert all(m.header.stamp.sec > 0 for m in seen)
    node.close()


@pytest.mark.slow
def test_streams_are_taken_only_while_a_page_is_open(viz) -> None:
    """As foxglove_bridge subscribes for its clients: without a page the visualizer decodes no /tf, odometry,
    scans, joint states or /clock (the latched /tf_static and description stay); the first page takes them,
    the last one to close drops them."""
    node = Probe("viz_graph_probe")
    live = {"/tf", "/joint_states", "/clock", "/diffbot_base_controller/odom", "/scan"}

    def viz_subscribed() -> set[str]:
        viz_nodes = {e.node for e in node.graph.subscribers("/tf_static") if e.node != node.name}
        return {t for t in node.graph.topics() for e in node.graph.subscribers(t) if e.node in viz_nodes}

    def settle(pred, what: str) -> set[str]:
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline:
            got = viz_subscribed()
            if pred(got):
                return got
            time.sleep(0.05)
        raise AssertionError(f"{what}: the visualizer subscribes {sorted(viz_subscribed())}")

    async def page() -> None:
        async with websockets.connect(f"{viz.ws_url}?token={viz.token}") as ws:
            await recv_until(ws, lambda m: m["type"] == "hello")
            got = await asyncio.to_thread(settle, lambda g: live <= g, "with a page open")
            assert "/tf_static" in got

    try:
        got = settle(lambda g: "/tf_static" in g, "before any page")
        assert not live & got
        asyncio.run(page())
        settle(lambda g: not live & g and "/tf_static" in g, "after the page closed")
    finally:
        node.close()


def test_wrong_token_foreign_origin_and_publisher_panel(viz) -> None:
    node = Probe("viz_test_listener")
    cmds = Recorder(node, CMD_TOPIC, "geometry_msgs/msg/TwistStamped")
    twists = Recorder(node, "/viz_test/cmd", "geometry_msgs/msg/Twist")
    stamped = Recorder(node, "/viz_test/stamped", "geometry_msgs/msg/TwistStamped")

    async def session() -> None:
        # Another web site in the same browser: refused at the handshake.
        with pytest.raises(InvalidStatus) as e:
            async with websockets.connect(viz.ws_url, origin="http://evil.example"):
                pass
        assert e.value.response.status_code == 403
        # A page with the wrong token can watch but not drive, and is told so.
        async with websockets.connect(f"{viz.ws_url}?token=wrong", origin=viz.base) as ws:
            hello = await recv_until(ws, lambda m: m["type"] == "hello")
            assert hello["authorized"] is False
            await ws.send(json.dumps({"op": "teleop", "linear": 0.5}))
            refused = await recv_until(ws, lambda m: m["type"] == "refused")
            assert "token" in refused["text"]
            await ws.send(
                json.dumps(
                    {
                        "op": "publish",
                        "topic": "/viz_test/cmd",
                        "type": "geometry_msgs/msg/Twist",
                        "body": "linear: {x: 1.0}",
                        "rate": 0,
                    }
                )
            )
            await recv_until(ws, lambda m: m["type"] == "refused")
            await ws.send(json.dumps({"op": "auth", "token": "still-wrong"}))
            assert (await recv_until(ws, lambda m: m["type"] == "auth"))["authorized"] is False
        # Without Origin (a script, not a browser page) and with the token: the publisher panel works.
        async with websockets.connect(f"{viz.ws_url}?token={viz.token}") as ws:
            await recv_until(ws, lambda m: m["type"] == "hello")
            tpl = {"op": "template", "type": "geometry_msgs/Twist"}
            await ws.send(json.dumps(tpl))
            t = await recv_until(ws, lambda m: m["type"] == "template")
            assert t["type_name"] == "geometry_msgs/msg/Twist" and "linear:" in t["yaml"]
            bad = {
                "op": "publish",
                "id": "a",
                "topic": "/viz_test/cmd",
                "type": "geometry_msgs/msg/Twist",
                "body": "linear: {q: 1.0}",
                "rate": 0,
            }
            await ws.send(json.dumps(bad))
            err = await recv_until(ws, lambda m: m["type"] == "error")
            assert "linear.q" in err["text"] and err["id"] == "a"
            await ws.send(json.dumps({**bad, "body": "linear: {x: .nan}"}))
            err = await recv_until(ws, lambda m: m["type"] == "error")
            assert "linear.x" in err["text"] and "NaN" in err["text"]
            once = {
                "op": "publish",
                "id": "b",
                "topic": "/viz_test/stamped",
                "type": "geometry_msgs/msg/TwistStamped",
                "body": "header: auto\ntwist: {linear: {x: 0.1}}",
            }
            await ws.send(json.dumps(once))
            assert (await recv_until(ws, lambda m: m["type"] == "publish_state"))["running"] is False
            await ws.send(json.dumps({**bad, "body": "linear: {x: 0.25}\nangular: {z: -0.5}", "rate": 20}))
            state = await recv_until(ws, lambda m: m["type"] == "publish_state")
            assert state["running"] is True and "20 Hz" in state["text"]
            await asyncio.sleep(1.0)
            await ws.send(json.dumps({"op": "publish_stop", "id": "a"}))
            assert (await recv_until(ws, lambda m: m["type"] == "publish_state"))["running"] is False

    asyncio.run(session())
    # Samples already in flight when the stop was acknowledged may still land: wait for the count to settle.
    n_at_stop = -1
    while n_at_stop != len(twists.snapshot()):
        n_at_stop = len(twists.snapshot())
        time.sleep(0.3)
    time.sleep(0.4)
    got = twists.snapshot()
    assert 12 <= n_at_stop <= 26, n_at_stop  # ~20 Hz for one second
    assert len(got) == n_at_stop  # stopped means stopped
    assert all(m.linear.x == 0.25 and m.angular.z == -0.5 for m in got)
    assert cmds.snapshot() == []  # nothing from the refused pages
    (one,) = stamped.snapshot()  # `header: auto` as in ros2 topic pub: stamped now
    assert one.twist.linear.x == 0.1 and one.header.stamp.sec > 0
    node.close()


def test_bad_rviz_file_exits_2_naming_it(tmp_path: Path, router, procs) -> None:
    bad = tmp_path / "broken.rviz"
    bad.write_text("Visualization Manager:\n  Displays:\n    - Class: rviz_default_plugins/Grid\n   bad: [\n")
    for path, detail in ((bad, rf"{re.escape(str(bad))}:\d+:\d+: malformed"), (tmp_path / "missing.rviz", "not found")):
        p = procs.diffctl("viz", "-d", str(path), "--port", "0")
        out, _ = p.communicate(timeout=30)
        assert p.returncode == 2, out
        assert re.search(detail, out) and str(path) in out and "Traceback" not in out
    colour = tmp_path / "colour.rviz"
    colour.write_text(
        "Visualization Manager:\n  Displays:\n    - Class: rviz_default_plugins/LaserScan\n      Color: 300; 0; 0\n"
    )
    p = procs.diffctl("viz", "-d", str(colour), "--port", "0")
    out, _ = p.communicate(timeout=30)
    assert p.returncode == 2 and "Displays[0].Color" in out and "300; 0; 0" in out


def test_a_taken_port_moves_to_the_next_free_one_and_bad_options_exit_2(router, procs, start_viz) -> None:
    with socket.socket() as s:  # another visualizer (or anything) holds the port asked for
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        v = start_viz("--port", str(port))
        shown = int(v.host_port.rsplit(":", 1)[1])
        assert shown > port, v.output()
        assert f"port {port} is taken" in v.output() and f"serving on port {shown}" in v.output()
        assert http_get(v.host_port, "/")[0] == 200
    p = procs.diffctl("viz", "--port", "0", "--ros-args", "-p", "max_linear_mps:=-1")
    out, _ = p.communicate(timeout=30)
    assert p.returncode == 2 and "max_linear_mps" in out and "-1" in out


def test_ignored_displays_listed_once_and_help(tmp_path: Path, router, procs, start_viz) -> None:
    f = tmp_path / "extra.rviz"
    f.write_text(
        (REPO / "config" / "diffbot.rviz")
        .read_text()
        .replace(
            "  Enabled: true\n  Global Options:",
            "    - Class: rviz_default_plugins/MarkerArray\n      Name: M1\n"
            "    - Class: rviz_default_plugins/MarkerArray\n      Name: M2\n  Enabled: true\n  Global Options:",
        )
    )
    v = start_viz("-d", str(f))
    v.proc.terminate()
    v.proc.wait(10)
    out = v.output()
    assert out.count("rviz_default_plugins/MarkerArray") == 1 and "not shown" in out
    h = subprocess.run([sys.executable, "-m", "diffctl", "viz", "--help"], capture_output=True, text=True, timeout=30)
    assert h.returncode == 0 and "Example" in h.stdout and "-d, --display-config" in h.stdout
