"""rmw_zenoh (Jazzy) wire format: key expressions, the 33-byte attachment, liveliness token keys, GIDs.

Reference: rmw_zenoh docs/design.md — data key `<domain>/<name>/<pkg>::msg::dds_::<Type>_/RIHS01_<hash>`,
attachment = zenoh-ext serialized (int64 seq, int64 source_timestamp_ns, uint8[16] gid), liveliness
`@ros2_lv/<domain>/<zid>/<node_id>/<entity_id>/<kind>/<enclave>/<ns>/<node>[/<topic>/<type>/<hash>/<qos>]`.
"""

from __future__ import annotations

import hashlib
import struct
from dataclasses import dataclass

from diffctl.bus.types import dds_name, from_dds_name, type_hash
from diffctl.errors import MessageError

LV_PREFIX = "@ros2_lv"
_ATT = struct.Struct("<qqB16s")
ATTACHMENT_SIZE = _ATT.size  # 33

KIND_NODE = "NN"
KIND_PUB = "MP"
KIND_SUB = "MS"
KIND_SERVICE = "SS"
KIND_CLIENT = "SC"

# RMW QoS enum values used in the token's qos field.
RELIABLE, BEST_EFFORT = 1, 2
VOLATILE, TRANSIENT_LOCAL = 2, 1
KEEP_LAST, KEEP_ALL = 1, 2


def strip(name: str) -> str:
    return name.strip("/")


def topic_key(domain: int, name: str, typename: str) -> str:
    return f"{domain}/{strip(name)}/{dds_name(typename)}/{type_hash(typename)}"


def service_key(domain: int, name: str, srv_typename: str) -> str:
    return topic_key(domain, name, srv_typename)


def pack_attachment(seq: int, timestamp_ns: int, gid: bytes) -> bytes:
    return _ATT.pack(seq, timestamp_ns, 16, gid)


def unpack_attachment(raw: bytes) -> tuple[int, int, bytes]:
    if len(raw) != ATTACHMENT_SIZE or raw[16] != 16:
        raise MessageError(f"attachment of {len(raw)} bytes is not the rmw_zenoh 33-byte layout")
    seq, ts, _, gid = _ATT.unpack(raw)
    return seq, ts, gid


def mangle(part: str) -> str:
    """Token field form: '/' → '%', empty → '%'."""
    return part.replace("/", "%") if part else "%"


def unmangle(part: str) -> str:
    return part.replace("%", "/")


def qos_string(*, reliable: bool = True, transient_local: bool = False, depth: int = 10) -> str:
    # Fields equal to rmw_zenoh's defaults (RELIABLE, VOLATILE, KEEP_LAST, depth 42) are left empty.
    rel = "" if reliable else str(BEST_EFFORT)
    dur = str(TRANSIENT_LOCAL) if transient_local else ""
    d = "" if depth == 42 else str(depth)
    return f"{rel}:{dur}:,{d}:,:,:,,"


def node_token(domain: int, zid: str, node_id: int, namespace: str, node: str) -> str:
    return f"{LV_PREFIX}/{domain}/{zid}/{node_id}/{node_id}/{KIND_NODE}/%/{mangle(namespace)}/{mangle(node)}"


def entity_token(
    domain: int, zid: str, node_id: int, entity_id: int, kind: str, namespace: str, node: str,
    topic: str, typename: str, qos: str,
) -> str:
    return (
        f"{LV_PREFIX}/{domain}/{zid}/{node_id}/{entity_id}/{kind}/%/{mangle(namespace)}/{mangle(node)}/"
        f"{mangle(topic)}/{dds_name(typename)}/{type_hash(typename)}/{qos}"
    )


def gid_of(token: str) -> bytes:
    # rmw_zenoh uses XXH3-128 of the token key; any stable 16-byte digest identifies the entity as well.
    return hashlib.blake2b(token.encode(), digest_size=16).digest()


@dataclass(frozen=True)
class Entity:
    """A parsed graph token."""

    zid: str
    node_id: str
    entity_id: str
    kind: str
    namespace: str
    node: str
    topic: str = ""
    type: str = ""
    type_hash: str = ""
    qos: str = ""

    @property
    def node_fqn(self) -> str:
        ns = self.namespace.rstrip("/")
        return f"{ns}/{self.node}" if ns else f"/{self.node}"

    @property
    def transient_local(self) -> bool:
        return self.qos.split(":")[1:2] == [str(TRANSIENT_LOCAL)]


def parse_token(key: str) -> Entity | None:
    parts = str(key).split("/")
    if len(parts) < 9 or parts[0] != LV_PREFIX:
        return None
    _, _domain, zid, nid, eid, kind, _enclave, ns, node, *rest = parts
    ns = unmangle(ns)
    node = unmangle(node)
    if kind == KIND_NODE:
        return Entity(zid, nid, eid, kind, ns if ns != "/" else "/", node)
    if len(rest) < 4:
        return None
    topic, dds, thash, qos = rest[0], rest[1], rest[2], "/".join(rest[3:])
    try:
        typename = from_dds_name(dds)
    except ValueError:
        typename = dds
    return Entity(zid, nid, eid, kind, ns if ns != "/" else "/", node, unmangle(topic), typename, thash, qos)
