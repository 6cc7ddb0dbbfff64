"""`diffctl foxglove-bridge` against a WebSocket client speaking the Foxglove protocol (the SDK server's
`foxglove.sdk.v1` subprotocol): advertise with ros2msg schemas, subscribe, a binary MessageData decoded
with the advertised schema alone, and a client-advertised cmd_vel published on the bus."""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import select
import struct
import threading
import time
from pathlib import Path
from typing import Any

import websockets
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

from diffctl.client.parameter import Parameter
from diffctl.interfaces import types
from tests.bag.test_files import one_error_line, run, write_bag
from tests.conftest import free_port, wait_port
from tests.probe import Probe, spinning

PROTOCOL = "foxglove.sdk.v1"


async def _read_until(ws: Any, pred, timeout_s: float = 30.0) -> Any:
    deadline = time.monotonic() + timeout_s
    while True:
        m = await asyncio.wait_for(ws.recv(), max(0.1, deadline - time.monotonic()))
        if pred(m):
            return m


async def subscribe_for_data(ws: Any, sub_id: int, channels: dict[str, dict], topic: str) -> tuple[dict, bytes]:
    """Subscribe to a topic's channel and return the channel and its first MessageData. The SDK's server sends a
    channel's advertise before it enters the channel in the connection's table (foxglove-sdk's
    ConnectedClient::advertise_channels): a client quick to subscribe to a channel advertised while it is connected
    is told "Unknown channel ID" (seen 2 in ~400 runs on a loaded machine; once all of 20 back-to-back retries in a
    quiet CI run). It waits a moment and subscribes again, to the topic's channel as last advertised."""

    for _ in range(40):
        ch = channels[topic]
        refused = f"Unknown channel ID: {ch['id']}"

        def answer(m: Any, refused: str = refused) -> bool:
            if isinstance(m, bytes):
                return m[0] == 1
            if json.loads(m).get("op") == "advertise":
                channels.update({c["topic"]: c for c in json.loads(m)["channels"]})
            return refused in m

        await ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": sub_id, "channelId": ch["id"]}]}))
        m = await _read_until(ws, answer)
        if isinstance(m, bytes):
            return ch, m
        await asyncio.sleep(0.05)
    raise AssertionError(f"{topic}'s channel stayed unknown to the server after 40 subscribes: {channels[topic]}")


def serving(bridge: Any, port: int, within_s: float = 60.0) -> None:
    """Wait for the bridge's "Foxglove server on ws://…" line: its port opens early in its start, and a
    handshake sent before every part is up could wait past the client's open timeout on a loaded machine.
    (Read from the descriptor itself: a buffered readline may hold that line while select sees nothing.)"""
    wait_port(port, within_s)
    deadline = time.monotonic() + within_s
    fd = bridge.stdout.fileno()
    seen = b""
    while b"Foxglove server on ws://" not in seen:
        left = deadline - time.monotonic()
        ready, _, _ = select.select([fd], [], [], max(0.0, left))
        chunk = os.read(fd, 65536) if ready else b""
        if not chunk:
            raise AssertionError(f"the bridge did not say it serves within {within_s} s: {seen.decode()!r}")
        seen += chunk


def connect(port: int, **kw: Any) -> Any:
    # a failure bound, not a guess of how long a handshake takes
    return websockets.connect(f"ws://127.0.0.1:{port}", subprotocols=[PROTOCOL], open_timeout=60, **kw)


async def until(condition: Any, act: Any, within_s: float = 60.0, every_s: float = 0.05) -> None:
    """Do `act()` every `every_s` until `condition()` holds (a failure after `within_s`)."""
    deadline = time.monotonic() + within_s
    while not condition():
        assert time.monotonic() < deadline, "condition not met within the bound"
        await act()
        await asyncio.sleep(every_s)


def decode_with_schema(name: str, schema: str, payload: bytes) -> Any:
    """Decode CDR with only what the server advertised (a fresh rosbags store, not diffctl's types)."""
    ts = get_typestore(Stores.EMPTY)
    ts.register(get_types_from_msg(schema, name))
    return ts.deserialize_cdr(payload, name)


def test_live_topics_subscribe_decode_and_client_publish(router: str, procs: Any) -> None:
    node = Probe("fg_test")
    gps = node.create_publisher("/gps", "sensor_msgs/msg/NavSatFix")  # in the graph first, but not whitelisted
    pub = node.create_publisher("/odom", "nav_msgs/msg/Odometry")
    cmds: list[Any] = []
    node.create_subscription("/cmd_vel", "geometry_msgs/msg/Twist", cmds.append)
    stop = threading.Event()

    def publish() -> None:
        i = 0
        while not stop.is_set():
            pub.publish({"header": {"frame_id": "odom"}, "pose": {"pose": {"position": {"x": 1.5 + i}}}})
            i += 1
            time.sleep(0.05)

    threading.Thread(target=publish, daemon=True).start()
    port = free_port()
    bridge = procs.diffctl("foxglove-bridge", "--port", str(port), "--ros-args", "-p", "topic_whitelist:=['/od.M']")
    serving(bridge, port)

    async def client() -> tuple[dict, Any]:
        async with connect(port) as ws:
            info = json.loads(await _read_until(ws, lambda m: isinstance(m, str) and '"serverInfo"' in m))
            assert "clientPublish" in info["capabilities"] and "cdr" in info["supportedEncodings"]
            channels: dict[str, dict] = {}

            def adv(m: Any) -> bool:
                if isinstance(m, str) and json.loads(m)["op"] == "advertise":
                    channels.update({c["topic"]: c for c in json.loads(m)["channels"]})
                return "/odom" in channels

            await _read_until(ws, adv)
            # topic_whitelist: a whole-name match, case ignored (upstream's ECMAScript icase regex_match)
            assert "/gps" not in channels, channels
            ch, data = await subscribe_for_data(ws, 7, channels, "/odom")
            sub_id, log_time = struct.unpack_from("<IQ", data, 1)
            assert sub_id == 7 and abs(log_time - time.time_ns()) < 60 * 10**9
            msg = decode_with_schema(ch["schemaName"], ch["schema"], data[13:])
            twist_def = types.store().generate_msgdef("geometry_msgs/msg/Twist", ros_version=2)[0]
            await ws.send(json.dumps({"op": "advertise", "channels": [
                {"id": 3, "topic": "/cmd_vel", "encoding": "cdr", "schemaName": "geometry_msgs/msg/Twist",
                 "schema": twist_def, "schemaEncoding": "ros2msg"}]}))
            cdr = types.serialize(types.new("geometry_msgs/msg/Twist", {"linear": {"x": 0.4},
                                                                       "angular": {"z": -0.2}}),
                                  "geometry_msgs/msg/Twist")
            await until(lambda: cmds, lambda: ws.send(struct.pack("<BI", 1, 3) + cdr))
            # The app may publish JSON too (its teleop panel on a server without ros2msg definitions).
            await ws.send(json.dumps({"op": "advertise", "channels": [
                {"id": 4, "topic": "/cmd_vel", "encoding": "json", "schemaName": "geometry_msgs/msg/Twist"}]}))
            await until(lambda: any(c.linear.x == 0.7 for c in cmds),
                        lambda: ws.send(struct.pack("<BI", 1, 4) + json.dumps({"linear": {"x": 0.7}}).encode()))
            return ch, msg

    ch, msg = asyncio.run(client())
    stop.set()
    assert (ch["encoding"], ch["schemaEncoding"], ch["schemaName"]) == ("cdr", "ros2msg", "nav_msgs/msg/Odometry")
    assert msg.header.frame_id == "odom" and msg.pose.pose.position.x >= 1.5
    assert cmds and cmds[0].linear.x == 0.4 and cmds[0].angular.z == -0.2
    assert any(c.linear.x == 0.7 and c.angular.z == 0.0 for c in cmds)
    procs.stop(bridge)
    gps.close()
    node.close()


def test_bag_playback_server(procs: Any, tmp_path: Path) -> None:
    bag = tmp_path / "b"
    write_bag(bag, n=10)
    port = free_port()
    server = procs.diffctl("foxglove-bridge", "--port", str(port), "--bag", str(bag))
    serving(server, port)

    async def client() -> tuple[dict, list[Any]]:
        async with connect(port) as ws:
            info = json.loads(await _read_until(ws, lambda m: isinstance(m, str) and '"serverInfo"' in m))
            adv = json.loads(await _read_until(ws, lambda m: isinstance(m, str) and '"advertise"' in m))
            ch = adv["channels"][0]
            # No wait between the two: the server handles a connection's messages in the order they came, so the
            # subscription is in place before playback starts.
            await ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": ch["id"]}]}))
            # The SDK's binary PlaybackControlRequest: op 3, command (0 play), speed f32, had-seek flag and
            # seek time u64, request id (u32 length + text).
            rid = b"r1"
            await ws.send(struct.pack("<BBfBQI", 3, 0, 4.0, 0, 0, len(rid)) + rid)
            got = []
            while len(got) < 10:
                m = await _read_until(ws, lambda m: isinstance(m, bytes) and m[0] == 1)
                got.append(decode_with_schema(ch["schemaName"], ch["schema"], m[13:]))
            return info, got

    info, got = asyncio.run(client())
    assert "time" in info["capabilities"]
    assert [m.pose.pose.position.x for m in got] == [0.25 * i for i in range(10)]
    procs.stop(server)


def test_non_loopback_address_is_refused() -> None:
    assert "loopback" in one_error_line(run("foxglove-bridge", "--address", "0.0.0.0", "--port", "0"))


def test_an_unknown_capability_is_refused_with_the_valid_ones() -> None:
    args = ("--port", "0", "--ros-args", "-p", "capabilities:=[services,sevrices]")
    line = one_error_line(run("foxglove-bridge", *args))
    assert "'sevrices' is not a foxglove_bridge capability" in line


def test_sim_time_is_the_servers_time(router: str, procs: Any) -> None:
    node = Probe("fg_clock")
    clock = node.create_publisher("/clock", "rosgraph_msgs/msg/Clock")
    port = free_port()
    bridge = procs.diffctl("foxglove-bridge", "--ros-args", "-p", f"port:={port}", "-p", "use_sim_time:=true")
    serving(bridge, port)

    async def client() -> tuple[dict, int]:
        async with connect(port) as ws:
            info = json.loads(await _read_until(ws, lambda m: isinstance(m, str) and '"serverInfo"' in m))
            # /clock is published until the first Time message (the bridge's subscription may match late)
            deadline = time.monotonic() + 60
            while time.monotonic() < deadline:
                clock.publish({"clock": {"sec": 42, "nanosec": 5}})
                try:
                    m = await asyncio.wait_for(ws.recv(), 0.1)
                except TimeoutError:
                    continue
                if isinstance(m, bytes) and m[0] == 2:
                    return info, struct.unpack_from("<Q", m, 1)[0]
            raise AssertionError("no Time message within 60 s")

    info, t = asyncio.run(client())
    assert "time" in info["capabilities"] and t == 42 * 10**9 + 5
    procs.stop(bridge)
    node.close()


ASCII_STL = (b"solid wedge\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n"
             b"  endloop\n endfacet\nendsolid wedge\n")


def _asset_workspace(root: Path) -> Path:
    """A user's workspace with one description package holding a mesh (found through the package index)."""
    pkg = root / "ws" / "src" / "wedge_description"
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>wedge_description</name><version>0.0.1</version>'
        "<description>d</description><maintainer email=\"a@b.c\">a</maintainer><license>MIT</license>"
        "<buildtool_depend>ament_cmake</buildtool_depend><export><build_type>ament_cmake</build_type></export>"
        "</package>\n")
    (pkg / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.8)\nproject(wedge_description)\nfind_package(ament_cmake REQUIRED)\n"
        "install(DIRECTORY meshes DESTINATION share/${PROJECT_NAME})\nament_package()\n")
    (pkg / "meshes" / "wedge.stl").write_bytes(ASCII_STL)
    return root / "ws"


def _cdr_of(schema_name: str, schema: str, values: dict[str, Any]) -> tuple[Any, bytes]:
    """A message encoded with only what the server advertised (a fresh rosbags store, which files a type by a
    msg-style name: `pkg/srv/T_Request` is registered as `pkg/msg/T_Request`)."""
    name = schema_name.replace("/srv/", "/msg/")
    ts = get_typestore(Stores.EMPTY)
    ts.register(get_types_from_msg(schema, name))
    return ts, ts.serialize_cdr(ts.types[name](**values), name)


def test_services_parameters_and_assets_as_foxglove_bridge_serves_them(router: str, procs: Any, tmp_path: Path) -> None:
    held = contextlib.ExitStack()
    node = held.enter_context(spinning("fg_params"))
    node.declare_parameter("gain", 0.5)
    node.declare_parameter("mode", "slow")
    calls: list[bool] = []

    def set_bool(req: Any) -> Any:
        calls.append(bool(req.data))
        return types.response("std_srvs/srv/SetBool", {"success": True, "message": f"was asked {req.data}"})

    node.bus_node.create_service("/fg_params/enable", "std_srvs/srv/SetBool", set_bool)
    ws_root = _asset_workspace(tmp_path)
    port = free_port()
    bridge = procs.diffctl("foxglove-bridge", "--port", str(port),
                           env={**os.environ, "DIFFCTL_WORKSPACE": str(ws_root)})
    serving(bridge, port)

    async def client() -> dict[str, Any]:
        out: dict[str, Any] = {}
        async with connect(port, max_size=None) as ws:
            info = json.loads(await _read_until(ws, lambda m: isinstance(m, str) and '"serverInfo"' in m))
            out["capabilities"] = info["capabilities"]
            services: dict[str, dict] = {}

            def adv(m: Any) -> bool:
                if isinstance(m, str) and json.loads(m)["op"] == "advertiseServices":
                    services.update({s["name"]: s for s in json.loads(m)["services"]})
                return "/fg_params/enable" in services

            await _read_until(ws, adv)
            svc = services["/fg_params/enable"]
            out["service"] = svc
            # serviceCallRequest (binary op 2): service id, call id, encoding, CDR payload.
            req = svc["request"]
            _, payload = _cdr_of(req["schemaName"], req["schema"], {"data": True})
            await ws.send(struct.pack("<BIII", 2, svc["id"], 77, 3) + b"cdr" + payload)
            reply = await _read_until(ws, lambda m: isinstance(m, bytes) and m[0] == 3)
            sid, call_id, enc_len = struct.unpack_from("<III", reply, 1)
            res = svc["response"]
            ts, _ = _cdr_of(res["schemaName"], res["schema"], {"success": False, "message": ""})
            out["call"] = (sid, call_id, reply[13:13 + enc_len].decode(),
                           ts.deserialize_cdr(reply[13 + enc_len:], res["schemaName"].replace("/srv/", "/msg/")))
            # A request in an encoding the ROS side cannot take is a call failure, not a crash.
            await ws.send(struct.pack("<BIII", 2, svc["id"], 78, 4) + b"json" + b"{}")
            out["failure"] = json.loads(await _read_until(
                ws, lambda m: isinstance(m, str) and '"serviceCallFailure"' in m))

            async def params(request: dict) -> dict:
                await ws.send(json.dumps(request))
                return json.loads(await _read_until(
                    ws, lambda m: isinstance(m, str) and '"parameterValues"' in m and f'"{request["id"]}"' in m))

            out["get"] = await params({"op": "getParameters", "parameterNames": ["/fg_params.gain",
                                                                                  "/fg_params.mode"], "id": "g1"})
            out["all"] = await params({"op": "getParameters", "parameterNames": [], "id": "g2"})
            await ws.send(json.dumps({"op": "subscribeParameterUpdates", "parameterNames": ["/fg_params.gain"]}))
            out["set"] = await params({"op": "setParameters", "id": "s1", "parameters": [
                {"name": "/fg_params.gain", "value": 2, "type": "float64"}]})
            out["node_after_set"] = node.get_parameter("gain").value
            # a change made on the ROS side reaches the watching client
            node.set_parameters([Parameter("gain", value=3.25)])
            update = await _read_until(ws, lambda m: isinstance(m, str) and '"parameterValues"' in m
                                       and "3.25" in m)
            out["update"] = json.loads(update)

            async def asset(uri: str, rid: int) -> tuple[int, bytes]:
                await ws.send(json.dumps({"op": "fetchAsset", "uri": uri, "requestId": rid}))
                m = await _read_until(ws, lambda m: isinstance(m, bytes) and m[0] == 4
                                      and struct.unpack_from("<I", m, 1)[0] == rid)
                status, err_len = struct.unpack_from("<BI", m, 5)
                return status, m[10:10 + err_len] if status else m[10 + err_len:]

            await ws.send(json.dumps({"op": "subscribeConnectionGraph"}))
            out["graph"] = json.loads(await _read_until(
                ws, lambda m: isinstance(m, str) and '"connectionGraphUpdate"' in m and "/fg_params/enable" in m))
            out["mesh"] = await asset("package://wedge_description/meshes/wedge.stl", 1)
            out["escape"] = await asset("package://wedge_description/../../../etc/passwd.stl", 2)
            out["unknown"] = await asset("package://no_such_package/meshes/a.stl", 3)
            out["not_listed"] = await asset("package://wedge_description/CMakeLists.txt", 4)
        return out

    out = asyncio.run(client())
    assert {"services", "parameters", "parametersSubscribe", "assets", "clientPublish"} <= set(out["capabilities"])
    svc = out["service"]
    assert svc["type"] == "std_srvs/srv/SetBool"
    assert (svc["request"]["schemaName"], svc["request"]["schemaEncoding"], svc["request"]["encoding"]) == (
        "std_srvs/srv/SetBool_Request", "ros2msg", "cdr")
    assert svc["response"]["schema"].split() == ["bool", "success", "string", "message"]
    sid, call_id, encoding, response = out["call"]
    assert (sid, call_id, encoding) == (svc["id"], 77, "cdr") and calls == [True]
    assert response.success and response.message == "was asked True"
    assert out["failure"]["callId"] == 78 and "encoding" in out["failure"]["message"].lower()
    got = {p["name"]: p for p in out["get"]["parameters"]}
    assert got["/fg_params.gain"]["value"] == 0.5 and got["/fg_params.gain"]["type"] == "float64"
    assert got["/fg_params.mode"]["value"] == "slow" and "type" not in got["/fg_params.mode"]
    every = {p["name"] for p in out["all"]["parameters"]}
    assert {"/fg_params.gain", "/fg_params.mode", "/fg_params.use_sim_time"} <= every
    assert not any(n.startswith("/foxglove_bridge.") for n in every)  # the bridge leaves itself out
    assert out["set"]["parameters"] == [{"name": "/fg_params.gain", "value": 2, "type": "float64"}]
    assert out["node_after_set"] == 2.0 and isinstance(out["node_after_set"], float)
    assert {"name": "/fg_params.gain", "value": 3.25, "type": "float64"} in out["update"]["parameters"]
    graph = out["graph"]
    assert {"name": "/fg_params/enable", "providerIds": ["/fg_params"]} in graph["advertisedServices"]
    published = {t["name"]: t["publisherIds"] for t in graph["publishedTopics"]}
    assert "/fg_params" in published["/parameter_events"] and "/fg_params" in published["/rosout"]
    assert {"services", "connectionGraph"} <= set(out["capabilities"])
    assert out["mesh"] == (0, ASCII_STL)
    assert out["escape"][0] == 1 and b"not allowed" in out["escape"][1]
    assert out["unknown"][0] == 1 and b"no_such_package" in out["unknown"][1]
    assert out["not_listed"][0] == 1 and b"not allowed" in out["not_listed"][1]
    procs.stop(bridge)
    held.close()
