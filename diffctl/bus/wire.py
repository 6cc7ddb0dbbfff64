"""rmw_zenoh (Jazzy) wire format: key expressions, the 33-byte attachment, liveliness token keys, GIDs.

Reference: rmw_zenoh docs/design.md — data key `<domain>/<name>/<pkg>::msg::dds_::<Type>_/RIHS01_<hash>`,
attachment = zenoh-ext serialized (int64 seq, int64 source_timestamp_ns, uint8[16] gid), liveliness
`@ros2_lv/<domain>/<zid>/<node_id>/<entity_id>/<kind>/<enclave>/<ns>/<node>[/<topic>/<type>/<hash>/<qos>]`.
"""

from __future__ import annotations

import struct
from collections.abc import Callable
from dataclasses import dataclass

import xxhash

from diffctl.errors import MessageError
from diffctl.interfaces.types import dds_name, from_dds_name, type_hash

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
AUTOMATIC, MANUAL_BY_TOPIC = 1, 3


def strip(name: str) -> str:
    return name.strip("/")


def topic_key(domain: int, name: str, typename: str) -> str:
    return f"{domain}/{strip(name)}/{dds_name(typename)}/{type_hash(typename)}"


def service_key(domain: int, name: str, srv_typename: str) -> str:
    return topic_key(domain, name, srv_typename)


def pack_attachment(seq: int, timestamp_ns: int, gid: bytes) -> bytes:
    return _ATT.pack(seq, timestamp_ns, 16, gid)


def attachment_packer(gid: bytes) -> Callable[[int, int], bytes]:
    """`pack(seq, timestamp_ns)` for one endpoint, its GID bound once (a publisher's per-message call)."""
    if len(gid) != 16:
        raise ValueError(f"a GID has 16 bytes, got {len(gid)}")
    att = _ATT.pack

    def pack(seq: int, timestamp_ns: int) -> bytes:
        return att(seq, timestamp_ns, 16, gid)

    return pack


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


_INFINITE_S, _INFINITE_NS = 9223372036, 854775807  # RMW_DURATION_INFINITE as rmw_zenoh splits it


@dataclass(frozen=True)
class QoS:
    """An endpoint's QoS as rmw_zenoh puts it in the liveliness token (durations in ns; None = infinite)."""

    reliable: bool = True
    transient_local: bool = False
    keep_all: bool = False
    depth: int = 10
    deadline_ns: int | None = None
    lifespan_ns: int | None = None
    manual_liveliness: bool = False  # MANUAL_BY_TOPIC (else AUTOMATIC)
    liveliness_lease_ns: int | None = None

    def __post_init__(self) -> None:
        if self.depth < 0:
            raise ValueError(f"QoS depth must be >= 0, got {self.depth}")

    def token(self) -> str:
        """`rel:dur:hist,depth:dl_s,dl_ns:ls_s,ls_ns:liv,lease_s,lease_ns`; rmw_zenoh's defaults left empty."""
        rel = "" if self.reliable else str(BEST_EFFORT)
        dur = str(TRANSIENT_LOCAL) if self.transient_local else ""
        hist = str(KEEP_ALL) if self.keep_all else ""
        # rmw_zenoh first adapts the profile: depth 0 (system default) becomes its default 42.
        depth = self.depth or 42
        d = "" if depth == 42 else str(depth)
        liv = str(MANUAL_BY_TOPIC) if self.manual_liveliness else ""
        return (f"{rel}:{dur}:{hist},{d}:{_duration(self.deadline_ns)}:{_duration(self.lifespan_ns)}:"
                f"{liv},{_duration(self.liveliness_lease_ns)}")

    @classmethod
    def parse(cls, text: str) -> QoS | None:
        """A token's QoS field back to a profile (None if it is not rmw_zenoh's six-group form)."""
        parts = text.split(":")
        if len(parts) < 6:
            return None
        try:
            hist, _, depth = parts[2].partition(",")
            liveliness, _, lease = parts[5].partition(",")
            return cls(
                reliable=parts[0] in ("", str(RELIABLE)), transient_local=parts[1] == str(TRANSIENT_LOCAL),
                keep_all=hist == str(KEEP_ALL), depth=int(depth) if depth else 42,
                deadline_ns=_parse_duration(parts[3]), lifespan_ns=_parse_duration(parts[4]),
                manual_liveliness=liveliness == str(MANUAL_BY_TOPIC), liveliness_lease_ns=_parse_duration(lease),
            )
        except ValueError:
            return None


def _duration(ns: int | None) -> str:
    if ns is None:
        return ","
    sec, nsec = divmod(int(ns), 1_000_000_000)
    return f"{'' if sec == _INFINITE_S else sec},{'' if nsec == _INFINITE_NS else nsec}"


def _parse_duration(text: str) -> int | None:
    sec, _, nsec = text.partition(",")
    if sec in ("", str(_INFINITE_S)) and nsec in ("", str(_INFINITE_NS)):
        return None
    return int(sec or 0) * 1_000_000_000 + int(nsec or 0)


def qos_string(*, reliable: bool = True, transient_local: bool = False, depth: int = 10) -> str:
    return QoS(reliable=reliable, transient_local=transient_local, depth=depth).token()


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
    """rmw_zenoh's GID: XXH3-128 (seed 0) of the liveliness key, low 64 bits then high, each little-endian."""
    return xxhash.xxh3_128_intdigest(token.encode()).to_bytes(16, "little")


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
    token: str = ""  # the liveliness key itself (rmw_zenoh derives the GID from it)

    @property
    def gid(self) -> bytes:
        return gid_of(self.token) if self.token else b""

    @property
    def node_fqn(self) -> str:
        ns = self.namespace.rstrip("/")
        return f"{ns}/{self.node}" if ns else f"/{self.node}"

    @property
    def transient_local(self) -> bool:
        return self.qos.split(":")[1:2] == [str(TRANSIENT_LOCAL)]

    @property
    def qos_profile(self) -> QoS | None:
        return QoS.parse(self.qos)


def parse_token(key: str) -> Entity | None:
    parts = str(key).split("/")
    if len(parts) < 9 or parts[0] != LV_PREFIX:
        return None
    _, _domain, zid, nid, eid, kind, _enclave, ns, node, *rest = parts
    ns = unmangle(ns)
    node = unmangle(node)
    if kind == KIND_NODE:
        return Entity(zid, nid, eid, kind, ns if ns != "/" else "/", node, token=str(key))
    if len(rest) < 4:
        return None
    topic, dds, thash, qos = rest[0], rest[1], rest[2], "/".join(rest[3:])
    try:
        typename = from_dds_name(dds)
    except ValueError:
        typename = dds
    return Entity(zid, nid, eid, kind, ns if ns != "/" else "/", node, unmangle(topic), typename, thash, qos,
                  str(key))
