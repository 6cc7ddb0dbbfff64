"""A running `diffctl launch sim_control` as ROS 2 Jazzy with rmw_zenoh sees it: every type hash any endpoint
announces equals rosidl's, and a publisher's attachment GID is XXH3-128 of its liveliness token key.

The graph is read with plain Zenoh (liveliness tokens, a raw subscriber), not with diffctl's own graph code.
"""

from __future__ import annotations

import threading
from pathlib import Path

import pytest
import xxhash
import zenoh

from diffctl.interfaces import types
from tests.e2e.stack import Stack
from tests.graph import jazzy_oracle

pytestmark = pytest.mark.slow

# rosidl's hashes for the controller_manager_msgs types with no wheel (a Jazzy build's generated sources).
NO_WHEEL = {
    "controller_manager_msgs/msg/HardwareComponentState":
        "RIHS01_0ed49e3b2669d3a540536dd4806a301612d0daf93a25bb1eebfd55817416026d",
}


def _tokens(session: zenoh.Session) -> list[str]:
    return [str(r.ok.key_expr) for r in session.liveliness().get("@ros2_lv/**", timeout=3.0) if r.ok is not None]


def test_sim_control_announces_jazzy_hashes_and_xxh3_gids(stack_env: str, tmp_path: Path) -> None:
    oracle = jazzy_oracle.hashes(jazzy_oracle.descriptions(jazzy_oracle.fetch()))
    stack = Stack("sim_control", tmp_path)
    try:
        stack.connect()
        stack.wait_controllers_active(("diffbot_base_controller", "joint_state_broadcaster"))
        conf = zenoh.Config()
        conf.insert_json5("mode", '"client"')
        conf.insert_json5("connect/endpoints", f'["{stack_env}"]')
        conf.insert_json5("scouting/multicast/enabled", "false")
        raw = zenoh.open(conf)
        try:
            keys = _tokens(raw)
            announced: dict[str, set[str]] = {}
            for k in keys:
                parts = k.split("/")
                if len(parts) >= 13 and parts[5] in ("MP", "MS", "SS", "SC"):
                    announced.setdefault(types.from_dds_name(parts[10]), set()).add(parts[11])
            checked = 0
            for typename, hashes in sorted(announced.items()):
                assert len(hashes) == 1, f"{typename} is announced with several hashes: {hashes}"
                want = oracle.get(typename) or NO_WHEEL.get(typename)
                if want is None:
                    continue
                assert hashes == {want}, f"{typename}: announced {hashes}, Jazzy has {want}"
                checked += 1
            for must in ("geometry_msgs/msg/TwistStamped", "nav_msgs/msg/Odometry", "sensor_msgs/msg/JointState",
                         "rosgraph_msgs/msg/Clock", "rcl_interfaces/msg/Log", "rcl_interfaces/srv/SetParameters",
                         "type_description_interfaces/srv/GetTypeDescription"):
                assert must in announced, f"nobody announces {must}"
            assert checked >= 15, sorted(announced)

            # /joint_states from joint_state_broadcaster: its sample's GID is XXH3-128 of its token key.
            token = next(k for k in keys if "/MP/" in k and "/%joint_states/" in k)
            got: list[bytes] = []
            done = threading.Event()

            def on_sample(s: zenoh.Sample) -> None:
                if s.attachment is not None and not done.is_set():
                    got.append(s.attachment.to_bytes())
                    done.set()

            sub = raw.declare_subscriber(f"{token.split('/')[1]}/joint_states/**", on_sample)
            assert done.wait(30.0), "no /joint_states sample"
            sub.undeclare()
            assert len(got[0]) == 33 and got[0][16] == 16
            assert got[0][17:] == xxhash.xxh3_128_intdigest(token.encode()).to_bytes(16, "little")
        finally:
            raw.close()
    finally:
        stack.stop()
