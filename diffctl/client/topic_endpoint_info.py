"""rclpy.topic_endpoint_info: what get_publishers_info_by_topic returns, read from graph tokens."""

from __future__ import annotations

import enum
from typing import Any

from diffctl.bus import wire
from diffctl.client.qos import HistoryPolicy, QoSPresetProfiles, from_wire
from diffctl.client.type_hash import TypeHash


class TopicEndpointTypeEnum(enum.IntEnum):
    INVALID = 0
    PUBLISHER = 1
    SUBSCRIPTION = 2


class TopicEndpointInfo:
    def __init__(self, node_name: str = "", node_namespace: str = "", topic_type: str = "",
                 topic_type_hash: Any = None, endpoint_type: TopicEndpointTypeEnum = TopicEndpointTypeEnum.INVALID,
                 endpoint_gid: list[int] | None = None, qos_profile: Any = None) -> None:
        """Every field may be left out: an empty info names no endpoint, an invalid type hash and the UNKNOWN
        QoS profile, as rclpy's does."""
        self.node_name = node_name
        self.node_namespace = node_namespace
        self.topic_type = topic_type
        self.topic_type_hash = TypeHash() if topic_type_hash is None else topic_type_hash
        self.endpoint_type = endpoint_type
        self.endpoint_gid = endpoint_gid or []
        self.qos_profile = QoSPresetProfiles.UNKNOWN.value if qos_profile is None else qos_profile

    @classmethod
    def from_entity(cls, e: wire.Entity) -> TopicEndpointInfo:
        kind = TopicEndpointTypeEnum.PUBLISHER if e.kind == wire.KIND_PUB else TopicEndpointTypeEnum.SUBSCRIPTION
        return cls(e.node, e.namespace if e.namespace.startswith("/") else "/" + e.namespace, e.type,
                   TypeHash.from_string(e.type_hash) if e.type_hash else TypeHash(), kind, list(e.gid),
                   from_wire(e.qos_profile))

    def __eq__(self, other: object) -> bool:
        return isinstance(other, TopicEndpointInfo) and vars(self) == vars(other)

    __hash__ = None  # type: ignore[assignment]

    def __str__(self) -> str:
        gid = ".".join(f"{b:02x}" for b in self.endpoint_gid)
        qos = self.qos_profile
        # a depth means something for KEEP_LAST only
        depth = f" ({qos.depth})" if qos.history == HistoryPolicy.KEEP_LAST else ""
        return "\n".join([
            f"Node name: {self.node_name}", f"Node namespace: {self.node_namespace}",
            f"Topic type: {self.topic_type}", f"Topic type hash: {self.topic_type_hash}",
            f"Endpoint type: {self.endpoint_type.name}", f"GID: {gid}", "QoS profile:",
            f"  Reliability: {qos.reliability.name}", f"  History (Depth): {qos.history.name}{depth}",
            f"  Durability: {qos.durability.name}", f"  Lifespan: {qos.lifespan}", f"  Deadline: {qos.deadline}",
            f"  Liveliness: {qos.liveliness.name}", f"  Liveliness lease duration: {qos.liveliness_lease_duration}",
        ])
