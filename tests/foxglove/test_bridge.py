"""`diffctl foxglove-bridge` against a WebSocket client speaking the Foxglove protocol (the SDK server's
`foxglove.sdk.v1` subprotocol): advertise with ros2msg schemas, subscribe, a binary MessageData decoded
with the advertised schema alone, and a client-advertised cmd_vel published on the bus."""

from __future__ import annotations

import asyncio
import json
import struct
import threading
import time
from pathlib import Path
from typing import Any

import websockets
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

from diffctl.bus import Node, types
from tests.bag.test_files import one_error_line, run, write_bag
from tests.conftest import free_port, wait_port

PROTOCOL = "foxglove.sdk.v1"


async def _read_until(ws: Any, pred, timeout_s: float = 30.0) -> Any:
    deadline = time.monotonic() + timeout_s
    while True:
        m = await asyncio.wait_for(ws.recv(), max(0.1, deadline - time.monotonic()))
        if pred(m):
            return m


def decode_with_schema(name: str, schema: str, payload: bytes) -> Any:
    """Decode CDR with only what the server advertised (a fresh rosbags store, not diffctl's types)."""
    ts = get_typestore(Stores.EMPTY)
    ts.register(get_types_from_msg(schema, name))
    return ts.deserialize_cdr(payload, name)


def test_live_topics_subscribe_decode_and_client_publish(router: str, procs: Any) -> None:
    node = Node("fg_test")
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
    bridge = procs.diffctl("foxglove-bridge", "--port", str(port))
    wait_port(port, 60)

    async def client() -> tuple[dict, Any]:
        async with websockets.connect(f"ws://127.0.0.1:{port}", subprotocols=[PROTOCOL]) as ws:
            info = json.loads(await _read_until(ws, lambda m: isinstance(m, str) and '"serverInfo"' in m))
            assert "clientPublish" in info["capabilities"] and "cdr" in info["supportedEncodings"]
            channels: dict[str, dict] = {}

            def adv(m: Any) -> bool:
                if isinstance(m, str) and json.loads(m)["op"] == "advertise":
                    channels.update({c["topic"]: c for c in json.loads(m)["channels"]})
                return "/odom" in channels

            await _read_until(ws, adv)
            ch = channels["/odom"]
            await ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": 7, "channelId": ch["id"]}]}))
            data = await _read_until(ws, lambda m: isinstance(m, bytes) and m[0] == 1)
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
            for _ in range(100):
                await ws.send(struct.pack("<BI", 1, 3) + cdr)
                await asyncio.sleep(0.05)
                if cmds:
                    break
            # The app may publish JSON too (its teleop panel on a server without ros2msg definitions).
            await ws.send(json.dumps({"op": "advertise", "channels": [
                {"id": 4, "topic": "/cmd_vel", "encoding": "json", "schemaName": "geometry_msgs/msg/Twist"}]}))
            for _ in range(100):
                await ws.send(struct.pack("<BI", 1, 4) + json.dumps({"linear": {"x": 0.7}}).encode())
                await asyncio.sleep(0.05)
                if any(c.linear.x == 0.7 for c in cmds):
                    break
            return ch, msg

    ch, msg = asyncio.run(client())
    stop.set()
    assert (ch["encoding"], ch["schemaEncoding"], ch["schemaName"]) == ("cdr", "ros2msg", "nav_msgs/msg/Odometry")
    assert msg.header.frame_id == "odom" and msg.pose.pose.position.x >= 1.5
    assert cmds and cmds[0].linear.x == 0.4 and cmds[0].angular.z == -0.2
    assert any(c.linear.x == 0.7 and c.angular.z == 0.0 for c in cmds)
    procs.stop(bridge)
    node.close()


def test_bag_playback_server(procs: Any, tmp_path: Path) -> None:
    bag = tmp_path / "b"
    write_bag(bag, n=10)
    port = free_port()
    server = procs.diffctl("foxglove-bridge", "--port", str(port), "--bag", str(bag))
    wait_port(port, 60)

    async def client() -> tuple[dict, list[Any]]:
        async with websockets.connect(f"ws://127.0.0.1:{port}", subprotocols=[PROTOCOL]) as ws:
            info = json.loads(await _read_until(ws, lambda m: isinstance(m, str) and '"serverInfo"' in m))
            adv = json.loads(await _read_until(ws, lambda m: isinstance(m, str) and '"advertise"' in m))
            ch = adv["channels"][0]
            await ws.send(json.dumps({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": ch["id"]}]}))
            await asyncio.sleep(0.3)
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


def test_sim_time_is_the_servers_time(router: str, procs: Any) -> None:
    node = Node("fg_clock")
    clock = node.create_publisher("/clock", "rosgraph_msgs/msg/Clock")
    port = free_port()
    bridge = procs.diffctl("foxglove-bridge", "--ros-args", "-p", f"port:={port}", "-p", "use_sim_time:=true")
    wait_port(port, 60)

    async def client() -> tuple[dict, int]:
        async with websockets.connect(f"ws://127.0.0.1:{port}", subprotocols=[PROTOCOL]) as ws:
            info = json.loads(await _read_until(ws, lambda m: isinstance(m, str) and '"serverInfo"' in m))
            for _ in range(200):
                clock.publish({"clock": {"sec": 42, "nanosec": 5}})
                try:
                    m = await asyncio.wait_for(ws.recv(), 0.1)
                except TimeoutError:
                    continue
                if isinstance(m, bytes) and m[0] == 2:
                    return info, struct.unpack_from("<Q", m, 1)[0]
            raise AssertionError("no Time message")

    info, t = asyncio.run(client())
    assert "time" in info["capabilities"] and t == 42 * 10**9 + 5
    procs.stop(bridge)
    node.close()
