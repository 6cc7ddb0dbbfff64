"""The type and QoS a topic tool takes from the publishers it relays, as topic_tools' ToolBaseNode chooses
them: depth 10, the first publisher's reliability and durability unless the publishers disagree (then
best effort, volatile: what matches them all), the longest deadline and lifespan, automatic liveliness."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Source:
    type_name: str
    qos: Any  # QoSProfile
    warnings: tuple[str, ...] = ()

    def key(self) -> tuple:
        q = self.qos
        return (self.type_name, int(q.reliability), int(q.durability), q.deadline.nanoseconds,
                q.lifespan.nanoseconds)


def choose(infos: Sequence[Any], topic: str) -> Source | None:
    """The source to relay from the publishers' endpoint infos (None: nobody publishes)."""
    from diffctl.client.duration import Duration
    from diffctl.client.qos import DurabilityPolicy, LivelinessPolicy, QoSProfile, ReliabilityPolicy

    if not infos:
        return None
    first = infos[0].qos_profile
    reliable = sum(1 for i in infos if i.qos_profile.reliability == ReliabilityPolicy.RELIABLE)
    latched = sum(1 for i in infos if i.qos_profile.durability == DurabilityPolicy.TRANSIENT_LOCAL)
    warnings = []
    reliability, durability = first.reliability, first.durability
    if 0 < reliable != len(infos):
        reliability = ReliabilityPolicy.BEST_EFFORT
        warnings.append(f"Some, but not all, publishers on topic {topic} offer 'reliable' reliability. Falling "
                        "back to 'best effort' reliability in orderto connect to all publishers.")
    if 0 < latched != len(infos):
        durability = DurabilityPolicy.VOLATILE
        warnings.append(f"Some, but not all, publishers on topic {topic} offer 'transient local' durability. "
                        "Falling back to 'volatile' durability in orderto connect to all publishers.")
    deadline = max(i.qos_profile.deadline.nanoseconds for i in infos)
    lifespan = max(i.qos_profile.lifespan.nanoseconds for i in infos)
    qos = QoSProfile(depth=10, reliability=reliability, durability=durability,
                     liveliness=LivelinessPolicy.AUTOMATIC, deadline=Duration(nanoseconds=deadline),
                     lifespan=Duration(nanoseconds=lifespan))
    return Source(infos[0].topic_type, qos, tuple(warnings))
