"""Bridge entries from ros_gz_bridge's YAML config and its `/TOPIC@ROS_TYPE@GZ_TYPE` command-line form.

Every entry is validated here, once: a missing key, an unknown key, a bad direction or an unsupported type
pair is a ConfigError naming the file, line, entry index and topic and listing what would be valid.
"""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass
from enum import Enum
from pathlib import Path
from typing import Any

import yaml

from diffctl.bridge.type_pairs import TYPE_PAIRS, TypePair, lookup, normalize_gz_type, normalize_ros_type
from diffctl.errors import ConfigError, suggest, yaml_error


class Direction(Enum):
    BIDIRECTIONAL = "BIDIRECTIONAL"
    GZ_TO_ROS = "GZ_TO_ROS"
    ROS_TO_GZ = "ROS_TO_GZ"

    @property
    def to_ros(self) -> bool:
        return self is not Direction.ROS_TO_GZ

    @property
    def to_gz(self) -> bool:
        return self is not Direction.GZ_TO_ROS


KEYS = (
    "topic_name",
    "ros_topic_name",
    "gz_topic_name",
    "ros_type_name",
    "gz_type_name",
    "direction",
    "lazy",
    "publisher_queue",
    "subscriber_queue",
    "qos_profile",
)
DEFAULT_QUEUE = 10


@dataclass(frozen=True)
class QosProfile:
    """An rclcpp QoS preset as the `qos_profile` key names it: its history depth (None: the entry's queue
    sizes) and reliability. None of the presets is transient local."""

    name: str
    depth: int | None
    reliable: bool


# rclcpp's presets (rclcpp/qos.hpp): SensorDataQoS keep-last 5 best effort, ClockQoS keep-last 1 best effort,
# ParametersQoS / ParameterEventsQoS keep-last 1000, ServicesQoS keep-last 10, the system default and
# best-available profiles take the configured depth, reliable.
QOS_PROFILES = {
    p.name: p
    for p in (
        QosProfile("SYSTEM_DEFAULT", None, True),
        QosProfile("DEFAULT", None, True),
        QosProfile("BEST_AVAILABLE", None, True),
        QosProfile("SENSOR_DATA", 5, False),
        QosProfile("CLOCK", 1, False),
        QosProfile("SERVICES_DEFAULT", 10, True),
        QosProfile("PARAMETERS", 1000, True),
        QosProfile("PARAMETER_EVENTS", 1000, True),
    )
}
# The command-line delimiters of parameter_bridge: `@` both ways, `[` gz→ros, `]` ros→gz.
CLI_DELIMITERS = {"@": Direction.BIDIRECTIONAL, "[": Direction.GZ_TO_ROS, "]": Direction.ROS_TO_GZ}


@dataclass(frozen=True)
class BridgeEntry:
    ros_topic: str
    gz_topic: str
    ros_type: str
    gz_type: str
    direction: Direction
    pair: TypePair
    lazy: bool = False
    publisher_queue: int = DEFAULT_QUEUE
    subscriber_queue: int = DEFAULT_QUEUE
    qos: QosProfile = QOS_PROFILES["SYSTEM_DEFAULT"]

    def __rich__(self) -> Any:
        return entries_table([self])

    @property
    def arrow(self) -> str:
        return {"BIDIRECTIONAL": "<->", "GZ_TO_ROS": "<-", "ROS_TO_GZ": "->"}[self.direction.value]


def entries_table(entries: list[BridgeEntry]) -> Any:
    from diffctl.console import table

    rows = [(e.ros_topic, e.ros_type, e.arrow, e.gz_topic, e.gz_type, "lazy" if e.lazy else "") for e in entries]
    return table("bridge", ["ROS topic", "ROS type", "", "gz topic", "gz type", ""], rows)


@dataclass(frozen=True)
class GzNamespace:
    """`expand_gz_topic_names`: gz names of config entries are expanded like ROS names of this node (rclcpp's
    expand_topic_or_service_name): absolute names stay, relative names go under the namespace, `~` under the
    node's own name."""

    namespace: str
    node_name: str

    def expand(self, name: str) -> str:
        ns = "/" + self.namespace.strip("/") if self.namespace.strip("/") else ""
        if name.startswith("/"):
            return name
        if name.startswith("~"):
            return f"{ns}/{self.node_name}" + ("/" + name[1:].lstrip("/") if name[1:].strip("/") else "")
        return f"{ns}/{name}"


def _entry_error(message: str, source: str | None, line: int | None, index: int, topic: str | None) -> ConfigError:
    field = f"entry {index}" + (f" ({topic})" if topic else "")
    return ConfigError(message, source=source, line=line, field=field)


# ROS names: tokens of letters, digits and '_' (not starting with a digit) joined by '/', optionally '~' first.
_ROS_NAME = re.compile(r"^(~/?|/)?([A-Za-z_][A-Za-z0-9_]*)(/[A-Za-z_][A-Za-z0-9_]*)*$")
# gz-transport names are freer, but they become Zenoh key expressions, where these characters are wildcards.
_GZ_FORBIDDEN = re.compile(r"[\s*$?#@\[\]]|//")


def _as_topic(value: Any, kind: str) -> str:
    if not isinstance(value, str) or not value.strip():
        raise ValueError(f"a topic name must be a non-empty string, got {value!r}")
    name = value.strip()
    if kind == "ros" and not _ROS_NAME.match(name):
        raise ValueError(
            f"ROS topic name {name!r} invalid; valid: letters, digits and '_' in '/'-separated tokens, "
            "none starting with a digit"
        )
    if kind == "gz" and (_GZ_FORBIDDEN.search(name) or not name.strip("/")):
        raise ValueError(f"gz topic name {name!r} invalid; valid: no spaces, '//' or any of * $ ? # @ [ ]")
    return name


def _as_queue(name: str, value: Any) -> int:
    if isinstance(value, str) and value.strip().isdigit():
        value = int(value)  # yaml-cpp's as<size_t> reads a quoted number too
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise ValueError(f"{name} {value!r} invalid; valid: an integer >= 1")
    return value


def _as_qos(value: Any) -> QosProfile:
    name = str(value).strip().upper() if isinstance(value, str) else ""
    if name not in QOS_PROFILES:
        raise ValueError(f"qos_profile {value!r} invalid; valid: {', '.join(QOS_PROFILES)}")
    return QOS_PROFILES[name]


def _as_bool(name: str, value: Any) -> bool:
    if isinstance(value, bool):
        return value
    if isinstance(value, str) and value.lower() in ("true", "false"):
        return value.lower() == "true"
    raise ValueError(f"{name} {value!r} invalid; valid: true, false")


def make_entry(
    item: dict[str, Any],
    index: int,
    source: str | None = None,
    line: int | None = None,
    gz_namespace: GzNamespace | None = None,
    key_lines: dict[str, int] | None = None,
) -> BridgeEntry:
    """One validated entry from a YAML map with ros_gz_bridge's keys (`key_lines`: line of each key)."""
    topic_hint = item.get("topic_name") or item.get("ros_topic_name") or item.get("gz_topic_name")
    topic_hint = topic_hint if isinstance(topic_hint, str) else None
    key_lines = key_lines or {}
    bad_key: list[str] = []  # the key a ValueError below is about, to point at its line

    def fail(message: str, key: str | None = None) -> ConfigError:
        return _entry_error(message, source, key_lines.get(key or "", line), index, topic_hint)

    for k in item:
        if k not in KEYS:
            raise fail(f"unknown key {k!r}{suggest(str(k), KEYS)}; valid keys: {', '.join(KEYS)}", str(k))
    try:
        bad_key[:] = ["topic_name" if "topic_name" in item else "ros_topic_name"]
        if "topic_name" in item:
            if "ros_topic_name" in item or "gz_topic_name" in item:
                raise ValueError("topic_name and ros_topic_name/gz_topic_name are mutually exclusive")
            ros_topic, gz_topic = _as_topic(item["topic_name"], "ros"), _as_topic(item["topic_name"], "gz")
        else:
            if "ros_topic_name" not in item and "gz_topic_name" not in item:
                raise ValueError("missing key: give topic_name, or ros_topic_name and gz_topic_name")
            ros_topic = _as_topic(item.get("ros_topic_name", item.get("gz_topic_name")), "ros")
            bad_key[:] = ["gz_topic_name"]
            gz_topic = _as_topic(item.get("gz_topic_name", item.get("ros_topic_name")), "gz")
        for k in ("ros_type_name", "gz_type_name"):
            bad_key[:] = [k]
            if k not in item:
                raise ValueError(f"missing key {k!r}")
            if not isinstance(item[k], str) or not item[k].strip():
                raise ValueError(f"{k} {item[k]!r} must be a type name such as 'geometry_msgs/msg/Twist'")
        bad_key[:] = ["direction"]
        direction_text = str(item.get("direction", "BIDIRECTIONAL")).strip().upper()
        if direction_text not in Direction.__members__:
            raise ValueError(f"direction {item.get('direction')!r} invalid; valid: {', '.join(Direction.__members__)}")
        bad_key[:] = ["lazy"]
        lazy = _as_bool("lazy", item.get("lazy", False))
        bad_key[:] = ["qos_profile"]
        qos = _as_qos(item.get("qos_profile", "SYSTEM_DEFAULT"))
        # An explicit queue size wins over the preset's depth.
        default_depth = qos.depth or DEFAULT_QUEUE
        bad_key[:] = ["publisher_queue"]
        pub_q = _as_queue("publisher_queue", item.get("publisher_queue", default_depth))
        bad_key[:] = ["subscriber_queue"]
        sub_q = _as_queue("subscriber_queue", item.get("subscriber_queue", default_depth))
    except ValueError as e:
        raise fail(str(e), bad_key[0] if bad_key else None) from None
    ros_type, gz_type = normalize_ros_type(item["ros_type_name"]), normalize_gz_type(item["gz_type_name"])
    pair = lookup(ros_type, gz_type)
    if pair is None:
        raise fail(f"unsupported type pair {ros_type} <-> {gz_type}; {pairs_near(ros_type, gz_type)}", "gz_type_name")
    if gz_namespace is not None:
        gz_topic = gz_namespace.expand(gz_topic)
    return BridgeEntry(ros_topic, gz_topic, ros_type, gz_type, Direction(direction_text), pair, lazy, pub_q, sub_q, qos)


def pairs_near(ros_type: str, gz_type: str, limit: int = 8) -> str:
    """The supported pairs a user most likely meant: those sharing either side, then close spellings of either.

    The whole table is ~60 pairs, unreadable on one line, so only the neighbours of the pair asked for are shown.
    Spellings are compared on the short names (`Temperature`, `Double`): the package prefixes are alike for all.
    """

    def short(name: str) -> str:
        return name.rsplit("/", 1)[-1].rsplit(".", 1)[-1]

    same_side = [p for p in TYPE_PAIRS if ros_type == p.ros_type or gz_type == p.gz_type]
    ros_near = set(difflib.get_close_matches(short(ros_type), {short(p.ros_type) for p in TYPE_PAIRS}, n=3, cutoff=0.6))
    gz_near = set(difflib.get_close_matches(short(gz_type), {short(p.gz_type) for p in TYPE_PAIRS}, n=3, cutoff=0.6))
    spelled = [p for p in TYPE_PAIRS if short(p.ros_type) in ros_near or short(p.gz_type) in gz_near]
    picked = list(dict.fromkeys(f"{p.ros_type}<->{p.gz_type}" for p in same_side + spelled))[:limit]
    if not picked:
        return f"no supported pair is close to it ({len(TYPE_PAIRS)} pairs supported, as in ros_gz_bridge)"
    return f"did you mean: {', '.join(picked)} ({len(TYPE_PAIRS)} pairs supported)"


def load_config(path: str | Path, gz_namespace: GzNamespace | None = None) -> list[BridgeEntry]:
    """Entries of a ros_gz_bridge YAML file (a YAML array of maps)."""
    p = Path(path)
    try:
        text = p.read_text()
    except FileNotFoundError:
        raise ConfigError("bridge config file not found", source=str(p)) from None
    except OSError as e:
        raise ConfigError(f"cannot read bridge config: {e.strerror}", source=str(p)) from None
    except UnicodeDecodeError as e:
        raise ConfigError(f"not a UTF-8 text file (byte {e.start}: {e.reason})", source=str(p)) from None
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
        data = yaml.safe_load(text)
    except yaml.YAMLError as e:
        raise yaml_error(e, str(p)) from None
    if data is None:
        return []
    if not isinstance(data, list):
        raise ConfigError(
            "a bridge config must be a YAML array of maps (one '- ros_topic_name: …' per topic)", source=str(p), line=1
        )
    entries = []
    for i, item in enumerate(data):
        node = root.value[i] if root is not None else None
        line = node.start_mark.line + 1 if node is not None else None
        if not isinstance(item, dict):
            raise _entry_error(f"must be a map of {', '.join(KEYS)}, got {item!r}", str(p), line, i, None)
        key_lines = {str(k.value): k.start_mark.line + 1 for k, _ in node.value} if node is not None else {}
        entries.append(make_entry(item, i, str(p), line, gz_namespace, key_lines))
    return entries


def parse_cli_entry(arg: str, index: int = 0) -> BridgeEntry:
    """`/TOPIC@ROS_TYPE@GZ_TYPE`, with `[` (gz→ros) or `]` (ros→gz) in place of the second `@`."""
    topic, sep, rest = arg.partition("@")

    def fail(message: str) -> ConfigError:
        return ConfigError(
            f"{message}; expected /TOPIC@ROS_TYPE@GZ_TYPE (or [ for gz->ros, ] for ros->gz)",
            field=f"argument {index} ({arg})",
        )

    if not sep or not topic:
        raise fail("no topic before '@'")
    positions = [(rest.find(d), d) for d in CLI_DELIMITERS if rest.find(d) >= 0]
    if not positions:
        raise fail("no delimiter between the ROS and the gz type")
    pos, delim = min(positions)
    ros_type, gz_type = rest[:pos], rest[pos + 1 :]
    if not ros_type or not gz_type or any(d in gz_type for d in CLI_DELIMITERS):
        raise fail("malformed bridge argument")
    item = {
        "topic_name": topic,
        "ros_type_name": ros_type,
        "gz_type_name": gz_type,
        "direction": CLI_DELIMITERS[delim].value,
    }
    try:
        return make_entry(item, index)
    except ConfigError as e:
        raise ConfigError(e.message, field=f"argument {index} ({arg})") from None
