"""Every structure without members (an empty message, most service requests, a feedback without fields) is
one uint8 on the wire, rosidl's `structure_needs_at_least_one_member`: 5 bytes with the CDR header. Checked for
every type of every package diffctl knows, through the client library's classes and the bus, against the
real rclpy's serialization where the Jazzy wheels have the package (rosidl's rule for the rest). Fast DDS's
serialize_message rounds a one-byte body up to 8 bytes (3 bytes of filler after it), so the real side is
compared as: the same size as its `std_msgs/UInt8()`, and the same first 5 bytes as ours."""

from __future__ import annotations

import json

from diffctl.client.interfaces import cls, serialize
from diffctl.interfaces import registry, types
from tests.oracle import jazzy_venv

PARTS = {"msg": [""], "srv": ["Request", "Response"], "action": ["Goal", "Result", "Feedback"]}
ROSIDL_EMPTY_SIZE = 4 + 1  # encapsulation header + the placeholder uint8

ORACLE = """
import importlib, json
from rclpy.serialization import serialize_message
from std_msgs.msg import UInt8
out = {"one uint8": serialize_message(UInt8()).hex()}
for name in NAMES:
    full, _, part = name.partition(".")
    pkg, kind, short = full.split("/")
    try:
        c = getattr(importlib.import_module(f"{pkg}.{kind}"), short)
    except ImportError:
        continue
    out[name] = serialize_message((getattr(c, part) if part else c)()).hex()
print(json.dumps(out))
"""


def _empty_structures() -> dict[str, tuple[type, str]]:
    """`pkg/kind/Name[.Part]` → (its class, the bus's type name) for every structure without members."""
    found = {}
    for pkg, p in sorted(registry.diffctl_packages().items()):
        for kind, names in p.interfaces.items():
            for short in names:
                c = cls(f"{pkg}/{kind}/{short}")
                for part in PARTS[kind]:
                    k = getattr(c, part) if part else c
                    if not k.get_fields_and_field_types():
                        bus = f"{pkg}/{kind}/{short}" + {"": "", "Request": "_Request", "Response": "_Response"}.get(
                            part, f"_{part}")
                        found[f"{pkg}/{kind}/{short}" + (f".{part}" if part else "")] = (k, bus)
    return found


def test_empty_structures_carry_rosidls_placeholder() -> None:
    empty = _empty_structures()
    # Known members of the set: controller_manager's list requests (diffctl's own texts), std_srvs', a msg.
    assert {"controller_manager_msgs/srv/ListControllers.Request", "std_srvs/srv/Trigger.Request",
            "std_msgs/msg/Empty", "tf2_msgs/action/LookupTransform.Feedback"} <= set(empty)
    ours = {name: len(serialize(k())) for name, (k, _) in empty.items()}
    bus = {name: len(types.serialize(types.new(t), t)) for name, (_, t) in empty.items() if "/action/" not in name}
    assert ours == dict.fromkeys(empty, ROSIDL_EMPTY_SIZE)
    assert bus == dict.fromkeys(bus, ROSIDL_EMPTY_SIZE)
    p = jazzy_venv.run_python(f"NAMES = {json.dumps(sorted(empty))}\n" + ORACLE)
    real = json.loads(p.stdout.strip().splitlines()[-1])
    one_uint8 = real.pop("one uint8")
    assert len(real) >= 10, real  # the Jazzy wheels have most of these packages
    assert {n: len(h) for n, h in real.items()} == dict.fromkeys(real, len(one_uint8))
    assert {n: h[: 2 * ROSIDL_EMPTY_SIZE] for n, h in real.items()} == {n: serialize(empty[n][0]()).hex()
                                                                          for n in real}
