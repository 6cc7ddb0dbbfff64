"""Every node (the client's Node, which every diffctl component is) is a ROS 2 node on the wire: parameter
services and events, /rosout, type descriptions, and rmw_zenoh's GIDs and QoS tokens — read back from the bus
with a bare probe, plain Zenoh and xxhash, not with the code under test."""

from __future__ import annotations

import subprocess
import sys
import threading
import time
from typing import Any

import xxhash
import zenoh

from diffctl.bus import wire
from diffctl.client.interfaces import cls
from diffctl.client.parameter import Parameter
from diffctl.interfaces import types
from tests.graph import jazzy_oracle
from tests.probe import Probe, spinning


def wait_for(pred, timeout_s: float = 10.0) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if pred():
            return True
        time.sleep(0.02)
    return bool(pred())


def tokens(session: zenoh.Session) -> list[str]:
    return [str(r.ok.key_expr) for r in session.liveliness().get("@ros2_lv/**", timeout=2.0) if r.ok is not None]


def test_parameter_services_events_and_descriptors(router: str) -> None:
    descriptor = cls("rcl_interfaces/msg/ParameterDescriptor")
    ranged = descriptor(description="m/s", floating_point_range=[
        cls("rcl_interfaces/msg/FloatingPointRange")(from_value=0.0, to_value=5.0, step=0.0)])
    probe = Probe("probe")
    events: list = []
    probe.create_subscription("/parameter_events", "rcl_interfaces/msg/ParameterEvent", events.append, depth=1000)
    with spinning("param_server", parameter_overrides=[Parameter("limit", value=2.0)]) as server:
        server.declare_parameter("limit", 1.0, ranged)
        server.declare_parameter("frame", "odom", descriptor(read_only=True))
        seen: list = []
        server.add_on_set_parameters_callback(
            lambda ps: seen.append({p.name: p.value for p in ps}) or cls("rcl_interfaces/msg/SetParametersResult")(
                successful=True))

        def call(short: str, srv: str, req: dict) -> Any:
            c = probe.create_client(f"/param_server/{short}", f"rcl_interfaces/srv/{srv}")
            assert c.wait_for_service(10.0), short
            return c.call(req, timeout=10.0)

        names = list(call("list_parameters", "ListParameters", {}).result.names)
        assert {"limit", "frame", "use_sim_time", "start_type_description_service"} <= set(names)
        values = call("get_parameters", "GetParameters", {"names": ["limit", "frame"]}).values
        assert (values[0].type, values[0].double_value) == (3, 2.0)  # the override
        assert (values[1].type, values[1].string_value) == (4, "odom")
        assert list(call("get_parameter_types", "GetParameterTypes", {"names": ["frame", "use_sim_time"]}).types) \
            == [4, 1]
        desc = call("describe_parameters", "DescribeParameters", {"names": ["limit", "frame"]}).descriptors
        assert desc[0].floating_point_range[0].to_value == 5.0 and desc[0].description == "m/s"
        assert desc[1].read_only

        results = call("set_parameters", "SetParameters", {"parameters": [
            {"name": "limit", "value": {"type": 3, "double_value": 4.5}},
            {"name": "limit", "value": {"type": 3, "double_value": 9.0}},
            {"name": "frame", "value": {"type": 4, "string_value": "map"}},
        ]}).results
        assert [r.successful for r in results] == [True, False, False]
        assert "range" in results[1].reason and "read-only" in results[2].reason
        assert server.get_parameter("limit").value == 4.5
        atomic = call("set_parameters_atomically", "SetParametersAtomically", {"parameters": [
            {"name": "limit", "value": {"type": 3, "double_value": 1.0}},
            {"name": "frame", "value": {"type": 4, "string_value": "map"}},
        ]}).result
        assert not atomic.successful and server.get_parameter("limit").value == 4.5, "all or nothing"
        assert {"limit": 4.5} in seen
        assert wait_for(lambda: any(e.node == "/param_server" and any(
            p.name == "limit" and p.value.double_value == 4.5 for p in e.changed_parameters) for e in events))
    probe.close()


def test_rosout_carries_log_lines_for_late_joiners(router: str, capfd) -> None:
    with spinning("talker") as talker:
        talker.get_logger().warning("wheel slip detected")
        line = capfd.readouterr().err
        assert "[WARN]" in line and "[talker]: wheel slip detected" in line, "console output is unchanged"
        time.sleep(0.5)
        got: list = []
        # A late subscriber with rcl's rosout QoS still gets the line (transient local, depth 1000).
        console = Probe("console")
        console.create_subscription("/rosout", "rcl_interfaces/msg/Log", got.append, latched=True, depth=1000)
        assert wait_for(lambda: any(m.msg == "wheel slip detected" for m in got))
        console.close()
    m = next(m for m in got if m.msg == "wheel slip detected")
    assert (m.level, m.name, m.function) == (30, "talker", "test_rosout_carries_log_lines_for_late_joiners")
    assert m.file.endswith("test_node_services.py") and m.line > 0 and m.stamp.sec > 0


def test_type_description_service_answers_for_types_in_use(router: str) -> None:
    oracle = jazzy_oracle.descriptions(jazzy_oracle.fetch())
    with spinning("user") as user:
        user.create_publisher(cls("geometry_msgs/msg/TwistStamped"), "/cmd_vel", 10)
        asker = Probe("asker")
        c = asker.create_client("/user/get_type_description", "type_description_interfaces/srv/GetTypeDescription")
        assert c.wait_for_service(10.0)
        want = oracle["geometry_msgs/msg/TwistStamped"]
        r = c.call({"type_name": "geometry_msgs/msg/TwistStamped",
                    "type_hash": want["type_hashes"][0]["hash_string"], "include_type_sources": True}, timeout=10.0)
        miss = c.call({"type_name": "sensor_msgs/msg/Imu", "type_hash": types.type_hash("sensor_msgs/msg/Imu")})
        asker.close()
    assert r.successful
    got = types.to_dict(r.type_description)
    assert got["type_description"] == want["type_description_msg"]["type_description"]
    assert got["referenced_type_descriptions"] == want["type_description_msg"]["referenced_type_descriptions"]
    assert r.type_sources[0].type_name == "geometry_msgs/msg/TwistStamped"
    assert not miss.successful and "not currently in use" in miss.failure_reason


def test_gid_is_xxh3_of_the_token_and_tokens_carry_the_real_qos(router: str) -> None:
    with spinning("gid_talker") as client_node:
        node = client_node.bus_node
        pub = node.create_publisher("/chatter", "std_msgs/msg/String", qos=wire.QoS(reliable=False, depth=7))
        latched = node.create_publisher("/latched", "std_msgs/msg/String", latched=True, depth=3)
        for i in range(5):
            latched.publish({"data": str(i)})
        raw = zenoh.open(_client_config(router))
        try:
            keys = tokens(raw)
            chatter = [k for k in keys if "/MP/" in k and "/gid_talker/%chatter/" in k]
            assert len(chatter) == 1, keys
            # rmw_zenoh's qos field: best effort (2), volatile default, keep_last default, depth 7.
            assert chatter[0].endswith("/2::,7:,:,:,,")
            assert any("/gid_talker/%latched/" in k and k.endswith("/:1:,3:,:,:,,") for k in keys)
            assert any("/gid_talker/%rosout/" in k and k.endswith("/:1:,1000:,:10,0:,,") for k in keys)
            assert any("/gid_talker/%parameter_events/" in k and k.endswith("/::,1000:,:,:,,") for k in keys)
            got: list[bytes] = []
            ready = threading.Event()

            def on_sample(s: zenoh.Sample) -> None:
                got.append(s.attachment.to_bytes())
                ready.set()

            sub = raw.declare_subscriber(f"{node.domain}/chatter/**", on_sample)
            assert wait_for(lambda: (pub.publish({"data": "hi"}), ready.is_set())[1], 10.0)
            att = got[0]
            assert len(att) == 33 and att[16] == 16, "rmw_zenoh >= 0.2.4 positional attachment"
            expected = xxhash.xxh3_128_intdigest(chatter[0].encode()).to_bytes(16, "little")
            assert att[17:] == expected
            sub.undeclare()
        finally:
            raw.close()
        # `topic info -v` shows that GID and the profile, as ros2 topic info -v does.
        out = subprocess.run([sys.executable, "-m", "diffctl", "topic", "info", "/chatter", "-v"],
                             capture_output=True, text=True, timeout=60).stdout
        assert f"GID: {expected.hex('.')}" in out, out
        assert "Reliability: BEST_EFFORT" in out and "History (Depth): KEEP_LAST (7)" in out
        # TRANSIENT_LOCAL depth 3: a late joiner gets the newest three.
        late: list = []
        late_probe = Probe("late")
        late_probe.create_subscription("/latched", "std_msgs/msg/String", late.append, latched=True, depth=3)
        assert wait_for(lambda: len(late) >= 3)
        time.sleep(0.3)
        late_probe.close()
    assert [m.data for m in late] == ["2", "3", "4"]


def _client_config(endpoint: str) -> zenoh.Config:
    conf = zenoh.Config()
    conf.insert_json5("mode", '"client"')
    conf.insert_json5("connect/endpoints", f'["{endpoint}"]')
    conf.insert_json5("scouting/multicast/enabled", "false")
    return conf


def test_use_sim_time_set_at_run_time_switches_the_clock(router: str) -> None:
    source = Probe("clock_source")
    clock = source.create_publisher("/clock", "rosgraph_msgs/msg/Clock")
    with spinning("timed") as node:
        assert node.get_clock().now().nanoseconds > 10**18
        assert node.set_parameters([Parameter("use_sim_time", value=True)])[0].successful
        assert wait_for(lambda: (clock.publish({"clock": {"sec": 42}}),
                                 node.get_clock().now().nanoseconds == 42 * 10**9)[1])
        assert node.set_parameters([Parameter("use_sim_time", value=False)])[0].successful
        assert node.get_clock().now().nanoseconds > 10**18, "back on the wall clock"
    source.close()
