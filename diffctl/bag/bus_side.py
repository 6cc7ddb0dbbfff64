"""What `bag play` needs from the bus, prepared before anything is published: the bag's types made
known (from its own schemas when diffctl lacks them), remaps parsed, one publisher per played topic
offering the recorded QoS (latched when every recorded offer was transient local, as rosbag2 re-offers).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from diffctl.bag.msgdefs import register_schema
from diffctl.bag.reader import Bag, Channel
from diffctl.errors import ConfigError
from diffctl.interfaces import types


def parse_remaps(items: tuple[str, ...]) -> dict[str, str]:
    out = {}
    for item in items:
        old, sep, new = item.partition(":=")
        if not sep or not old.strip() or not new.strip():
            raise ConfigError(f"--remap {item!r} is not OLD:=NEW", hint="e.g. --remap /odom:=/replayed/odom")
        out["/" + old.strip().lstrip("/")] = "/" + new.strip().lstrip("/")
    return out


@dataclass(frozen=True)
class PlayedTopic:
    topic: str  # as recorded
    out_topic: str  # after remapping
    type: str
    latched: bool
    depth: int


def plan_topics(bag: Bag, wanted: tuple[str, ...], remaps: dict[str, str], drop: set[str],
                warn: Callable[[str], None] = print) -> list[PlayedTopic]:
    """The topics to play, with every type made known; raises before anything starts. `warn` takes what is
    worth saying but plays anyway (the player's node logs it once it exists)."""
    channels = bag.channels()
    if wanted:
        unknown = [t for t in wanted if ("/" + t.lstrip("/")) not in channels]
        if unknown:
            raise ConfigError(f"--topics: {', '.join(unknown)} not in the bag",
                              hint="its topics: " + ", ".join(sorted(channels)))
    selected = {("/" + t.lstrip("/")) for t in wanted} if wanted else set(channels)
    out = []
    for topic in sorted(selected - drop):
        ch = channels[topic]
        _check_channel(ch, str(bag.path))
        register_schema(ch.type, ch.schema_encoding, ch.schema_text, f"{bag.path}: {topic}")
        ours = types.type_hash(ch.type)
        if ch.type_hash and ch.type_hash != ours:
            warn(f"{topic}: the bag's {ch.type} hashes to {ch.type_hash} but this definition to {ours}; "
                 "subscribers of the recorded definition will not match")
        latched = bool(ch.qos) and all(q.durability == "transient_local" for q in ch.qos)
        depth = max((q.depth for q in ch.qos), default=10) or 10
        out.append(PlayedTopic(topic, remaps.get(topic, topic), ch.type, latched, depth))
    return out


def _check_channel(ch: Channel, source: str) -> None:
    if ch.message_encoding != "cdr":
        raise ConfigError(f"topic {ch.topic} is encoded as {ch.message_encoding!r}", source=source,
                          hint="ROS 2 bags hold cdr messages")
    if not ch.type or not ch.schema_text:
        raise ConfigError(f"topic {ch.topic} has no schema, so its type cannot be known", source=source)


def make_publishers(node: Any, played: list[PlayedTopic]) -> dict[str, Any]:
    """Recorded topic → publish(cdr) on its (remapped) name."""
    out = {}
    for p in played:
        pub = node.create_publisher(p.out_topic, p.type, latched=p.latched, depth=p.depth)
        out[p.topic] = pub.publish_raw
    return out
