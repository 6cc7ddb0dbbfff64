"""rosbag2's `metadata.yaml` (rosbag2_bagfile_information, versions 1 to 9) and the QoS profiles inside it.

Reading follows rosbag2_storage's yaml codec: every key that the declared version introduced must be there
(yaml-cpp throws otherwise), `offered_qos_profiles` is a YAML string with integer enums up to version 8
and a real list with string enums from version 9. Writing produces version 9, as Jazzy does.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import yaml

from diffctl.errors import ConfigError, yaml_error

VERSION = 9
TOP_KEY = "rosbag2_bagfile_information"
INFINITE = {"sec": 9223372036, "nsec": 854775807}

# RMW enum values (rmw/types.h) ↔ the strings version 9 writes.
_HISTORY = {0: "system_default", 1: "keep_last", 2: "keep_all", 3: "unknown"}
_RELIABILITY = {0: "system_default", 1: "reliable", 2: "best_effort", 3: "unknown", 4: "best_available"}
_DURABILITY = {0: "system_default", 1: "transient_local", 2: "volatile", 3: "unknown", 4: "best_available"}
_LIVELINESS = {0: "system_default", 1: "automatic", 3: "manual_by_topic", 4: "unknown", 5: "best_available"}
_POLICIES = {"history": _HISTORY, "reliability": _RELIABILITY, "durability": _DURABILITY,
             "liveliness": _LIVELINESS}
_DURATIONS = ("deadline", "lifespan", "liveliness_lease_duration")


@dataclass(frozen=True)
class Qos:
    """One offered QoS profile, policies as version 9 strings, durations as (sec, nsec)."""

    history: str = "keep_last"
    depth: int = 10
    reliability: str = "reliable"
    durability: str = "volatile"
    deadline: tuple[int, int] = (INFINITE["sec"], INFINITE["nsec"])
    lifespan: tuple[int, int] = (INFINITE["sec"], INFINITE["nsec"])
    liveliness: str = "automatic"
    liveliness_lease_duration: tuple[int, int] = (INFINITE["sec"], INFINITE["nsec"])
    avoid_ros_namespace_conventions: bool = False

    def to_dict(self, version: int = VERSION) -> dict[str, Any]:
        out: dict[str, Any] = {}
        for name in ("history", "depth", "reliability", "durability", "deadline", "lifespan", "liveliness",
                     "liveliness_lease_duration", "avoid_ros_namespace_conventions"):
            value = getattr(self, name)
            if name in _POLICIES and version < 9:
                value = {v: k for k, v in _POLICIES[name].items()}[value]
            elif name in _DURATIONS:
                value = {"sec": value[0], "nsec": value[1]}
            out[name] = value
        return out

    @classmethod
    def from_dict(cls, d: Any, where: str) -> Qos:
        if not isinstance(d, dict):
            raise ConfigError(f"{where}: a QoS profile must be a mapping, got {d!r}")
        kw: dict[str, Any] = {}
        for name, table in _POLICIES.items():
            if name in d:
                kw[name] = _policy(d[name], table, f"{where}.{name}")
        if "depth" in d:
            kw["depth"] = _int(d["depth"], f"{where}.depth")
        for name in _DURATIONS:
            if name in d:
                v = d[name]
                if not isinstance(v, dict) or "sec" not in v or "nsec" not in v:
                    raise ConfigError(f"{where}.{name}: expected {{sec: S, nsec: N}}, got {v!r}")
                kw[name] = (_int(v["sec"], f"{where}.{name}.sec"), _int(v["nsec"], f"{where}.{name}.nsec"))
        if "avoid_ros_namespace_conventions" in d:
            kw["avoid_ros_namespace_conventions"] = bool(d["avoid_ros_namespace_conventions"])
        return cls(**kw)


def _policy(value: Any, table: dict[int, str], where: str) -> str:
    if isinstance(value, int) and not isinstance(value, bool) and value in table:
        return table[value]
    if isinstance(value, str) and value in table.values():
        return value
    raise ConfigError(f"{where}: unknown QoS policy value {value!r}",
                      hint="valid: " + ", ".join(f"{k}/{v}" for k, v in table.items()))


def _int(value: Any, where: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise ConfigError(f"{where}: expected an integer, got {value!r}")
    return value


def qos_list_to_yaml(profiles: list[Qos], version: int = VERSION) -> str:
    """The `offered_qos_profiles` string rosbag2 stores in MCAP channel metadata (and in v4–8 metadata)."""
    return yaml.safe_dump([p.to_dict(version) for p in profiles], sort_keys=False, default_flow_style=False)


def qos_list_from(value: Any, where: str) -> list[Qos]:
    """Both forms: a YAML string (v4–8, MCAP channel metadata) or a list (v9)."""
    if value is None or value == "":
        return []
    if isinstance(value, str):
        try:
            value = yaml.safe_load(value)
        except yaml.YAMLError as e:
            raise ConfigError(f"{where}: offered_qos_profiles is not valid YAML: {e}") from None
        if value is None:
            return []
    if not isinstance(value, list):
        raise ConfigError(f"{where}: offered_qos_profiles must be a list of QoS profiles, got {value!r}")
    return [Qos.from_dict(d, f"{where}[{i}]") for i, d in enumerate(value)]


@dataclass(frozen=True)
class TopicInfo:
    name: str
    type: str
    serialization_format: str = "cdr"
    offered_qos_profiles: tuple[Qos, ...] = ()
    type_description_hash: str = ""
    message_count: int = 0


@dataclass(frozen=True)
class FileInfo:
    path: str
    starting_time_ns: int
    duration_ns: int
    message_count: int


@dataclass(frozen=True)
class BagMetadata:
    """What `metadata.yaml` holds, whatever version it was read from."""

    version: int = VERSION
    storage_identifier: str = "mcap"
    relative_file_paths: tuple[str, ...] = ()
    starting_time_ns: int = 0
    duration_ns: int = 0
    message_count: int = 0
    topics: tuple[TopicInfo, ...] = ()
    compression_format: str = ""
    compression_mode: str = ""
    files: tuple[FileInfo, ...] = ()
    custom_data: dict[str, str] = field(default_factory=dict)
    ros_distro: str = ""

    @property
    def end_ns(self) -> int:
        return self.starting_time_ns + self.duration_ns

    def with_files(self, files: list[FileInfo]) -> BagMetadata:
        return replace(self, files=tuple(files), relative_file_paths=tuple(f.path for f in files))

    def to_dict(self) -> dict[str, Any]:
        """Version 9, in rosbag2's key order."""
        topics = []
        for t in self.topics:
            topics.append({
                "topic_metadata": {
                    "name": t.name,
                    "type": t.type,
                    "serialization_format": t.serialization_format,
                    "offered_qos_profiles": [q.to_dict() for q in t.offered_qos_profiles],
                    "type_description_hash": t.type_description_hash,
                },
                "message_count": t.message_count,
            })
        return {TOP_KEY: {
            "version": VERSION,
            "storage_identifier": self.storage_identifier,
            "duration": {"nanoseconds": self.duration_ns},
            "starting_time": {"nanoseconds_since_epoch": self.starting_time_ns},
            "message_count": self.message_count,
            "topics_with_message_count": topics,
            "compression_format": self.compression_format,
            "compression_mode": self.compression_mode,
            "relative_file_paths": list(self.relative_file_paths),
            "files": [{"path": f.path, "starting_time": {"nanoseconds_since_epoch": f.starting_time_ns},
                       "duration": {"nanoseconds": f.duration_ns}, "message_count": f.message_count}
                      for f in self.files],
            "custom_data": dict(self.custom_data) or None,
            "ros_distro": self.ros_distro,
        }}

    def dump(self) -> str:
        return yaml.safe_dump(self.to_dict(), sort_keys=False, default_flow_style=False, width=1000)

    def write(self, bag_dir: Path) -> None:
        tmp = bag_dir / "metadata.yaml.tmp"
        tmp.write_text(self.dump())
        tmp.replace(bag_dir / "metadata.yaml")  # a crash never leaves half a metadata file


# Keys each version introduced (cumulative), as rosbag2_storage/yaml.hpp decodes them.
_REQUIRED = (
    (1, ("version", "storage_identifier", "relative_file_paths", "duration", "starting_time", "message_count",
         "topics_with_message_count")),
    (3, ("compression_format", "compression_mode")),
    (5, ("files",)),
    (6, ("custom_data",)),
    (8, ("ros_distro",)),
)


def _get(d: dict[str, Any], key: str, where: str) -> Any:
    if key not in d:
        raise ConfigError(f"{where}: missing key {key!r}", hint=f"present: {', '.join(map(str, d)) or '(none)'}")
    return d[key]


def _nested_int(d: dict[str, Any], key: str, inner: str, where: str) -> int:
    v = _get(d, key, where)
    if not isinstance(v, dict):
        raise ConfigError(f"{where}.{key}: expected {{{inner}: N}}, got {v!r}")
    return _int(_get(v, inner, f"{where}.{key}"), f"{where}.{key}.{inner}")


def parse(text: str, source: str) -> BagMetadata:
    """`metadata.yaml` text → BagMetadata; any missing or ill-typed field is a ConfigError naming it."""
    try:
        doc = yaml.safe_load(text)
    except yaml.YAMLError as e:
        raise yaml_error(e, source) from None
    if not isinstance(doc, dict) or TOP_KEY not in doc or not isinstance(doc[TOP_KEY], dict):
        raise ConfigError(f"not a rosbag2 metadata file: the top-level key {TOP_KEY!r} is missing", source=source)
    d = doc[TOP_KEY]
    w = TOP_KEY
    version = _int(_get(d, "version", w), f"{w}.version")
    if not 1 <= version <= VERSION:
        raise ConfigError(f"{w}.version: unsupported metadata version {version}", source=source,
                          hint=f"versions 1 to {VERSION} are read")
    try:
        for since, keys in _REQUIRED:
            if version >= since:
                for k in keys:
                    _get(d, k, w)
        paths = _get(d, "relative_file_paths", w)
        if not isinstance(paths, list) or not all(isinstance(p, str) for p in paths):
            raise ConfigError(f"{w}.relative_file_paths: expected a list of file names, got {paths!r}")
        topics = []
        for i, entry in enumerate(_get(d, "topics_with_message_count", w) or []):
            tw = f"{w}.topics_with_message_count[{i}]"
            if not isinstance(entry, dict):
                raise ConfigError(f"{tw}: expected a mapping, got {entry!r}")
            tm = _get(entry, "topic_metadata", tw)
            mw = f"{tw}.topic_metadata"
            if not isinstance(tm, dict):
                raise ConfigError(f"{mw}: expected a mapping, got {tm!r}")
            qos = qos_list_from(_get(tm, "offered_qos_profiles", mw), f"{mw}.offered_qos_profiles") \
                if version >= 4 else []
            topics.append(TopicInfo(
                name=str(_get(tm, "name", mw)), type=str(_get(tm, "type", mw)),
                serialization_format=str(_get(tm, "serialization_format", mw)),
                offered_qos_profiles=tuple(qos),
                type_description_hash=str(_get(tm, "type_description_hash", mw) or "") if version >= 7 else "",
                message_count=_int(_get(entry, "message_count", tw), f"{tw}.message_count"),
            ))
        files = []
        for i, f in enumerate(d.get("files") or [] if version >= 5 else []):
            fw = f"{w}.files[{i}]"
            if not isinstance(f, dict):
                raise ConfigError(f"{fw}: expected a mapping, got {f!r}")
            files.append(FileInfo(str(_get(f, "path", fw)),
                                  _nested_int(f, "starting_time", "nanoseconds_since_epoch", fw),
                                  _nested_int(f, "duration", "nanoseconds", fw),
                                  _int(_get(f, "message_count", fw), f"{fw}.message_count")))
        custom = d.get("custom_data") or {}
        if not isinstance(custom, dict):
            raise ConfigError(f"{w}.custom_data: expected a mapping of strings, got {custom!r}")
        return BagMetadata(
            version=version,
            storage_identifier=str(_get(d, "storage_identifier", w)),
            relative_file_paths=tuple(paths),
            starting_time_ns=_nested_int(d, "starting_time", "nanoseconds_since_epoch", w),
            duration_ns=_nested_int(d, "duration", "nanoseconds", w),
            message_count=_int(_get(d, "message_count", w), f"{w}.message_count"),
            topics=tuple(topics),
            compression_format=str(d.get("compression_format") or ""),
            compression_mode=str(d.get("compression_mode") or ""),
            files=tuple(files),
            custom_data={str(k): str(v) for k, v in custom.items()},
            ros_distro=str(d.get("ros_distro") or ""),
        )
    except ConfigError as e:
        if e.source is None:
            e.source = source
        raise


def load(path: Path) -> BagMetadata:
    try:
        text = path.read_text()
    except OSError as e:
        raise ConfigError(f"cannot read the bag metadata: {e.strerror}", source=str(path)) from None
    return parse(text, str(path))
