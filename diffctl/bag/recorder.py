"""The recorder of `bag record`: raw CDR subscriptions to every selected topic of the graph, as they appear.

Samples are taken as received — payload bytes, the rmw_zenoh attachment's sequence number and source
timestamp — and handed to one writer thread, so Zenoh's threads never wait on the disk. Topics that
appear later are picked up from the graph's liveliness events; latched topics are subscribed with
history (transient local), so /robot_description and /tf_static published long before are recorded too.
"""

from __future__ import annotations

import queue
import re
import threading
import time
from dataclasses import dataclass
from typing import Any

from diffctl.bag.metadata import INFINITE, Qos
from diffctl.bag.msgdefs import ros2msg
from diffctl.bag.writer import BagWriter
from diffctl.bus import wire
from diffctl.errors import ConfigError
from diffctl.interfaces import types

FLUSH_PERIOD_S = 1.0  # bytes reach the OS at least this often, so a killed recorder loses little
_Idle = object()  # nothing arrived for a flush period


@dataclass(frozen=True)
class Selection:
    """Which topics `bag record` takes, as its -a / TOPIC… / --regex / --exclude-regex options say."""

    all_topics: bool = False
    topics: tuple[str, ...] = ()
    regex: str = ""
    exclude_regex: str = ""
    include_hidden: bool = False

    def __post_init__(self) -> None:
        if not (self.all_topics or self.topics or self.regex):
            raise ConfigError("nothing to record", hint="give topics, -a/--all or -e/--regex REGEX")
        for opt, rx in (("--regex", self.regex), ("--exclude-regex", self.exclude_regex)):
            if rx:
                try:
                    re.compile(rx)
                except re.error as e:
                    raise ConfigError(f"{opt} {rx!r} is not a valid regular expression: {e}") from None

    def wants(self, topic: str) -> bool:
        if self.exclude_regex and re.search(self.exclude_regex, topic):
            return False
        if topic in self.topics:
            return True  # named explicitly: hidden or not
        if self.regex and re.search(self.regex, topic):
            return True
        hidden = any(part.startswith("_") for part in topic.split("/"))
        return self.all_topics and (self.include_hidden or not hidden)


def qos_from_token(field: str) -> Qos:
    """rmw_zenoh's token QoS text (`rel:dur:hist,depth:dl_s,dl_ns:ls_s,ls_ns:liv,lease_s,lease_ns`, empty =
    rmw_zenoh's default) → the profile rosbag2 stores as offered_qos_profiles."""
    parts = field.split(":")
    parts += [""] * (6 - len(parts))

    def num(text: str, default: int) -> int:
        try:
            return int(text) if text else default
        except ValueError:
            return default

    def pair(text: str, default: tuple[int, int]) -> tuple[int, int]:
        a, _, b = text.partition(",")
        return num(a, default[0]), num(b, default[1])

    inf = (INFINITE["sec"], INFINITE["nsec"])
    hist, _, depth = parts[2].partition(",")
    liv, _, lease = parts[5].partition(",")
    return Qos(
        history="keep_all" if num(hist, 1) == wire.KEEP_ALL else "keep_last",
        depth=num(depth, 42),
        reliability="best_effort" if num(parts[0], 1) == wire.BEST_EFFORT else "reliable",
        durability="transient_local" if num(parts[1], 2) == wire.TRANSIENT_LOCAL else "volatile",
        deadline=pair(parts[3], inf),
        lifespan=pair(parts[4], inf),
        liveliness="manual_by_topic" if num(liv, 1) == 3 else "automatic",
        liveliness_lease_duration=pair(lease, inf),
    )


@dataclass(frozen=True)
class _NewTopic:
    topic: str
    type: str
    schema_text: str
    offered: tuple[Qos, ...]
    type_hash: str


@dataclass(frozen=True)
class _Sample:
    topic: str
    data: bytes
    log_time_ns: int
    publish_time_ns: int
    sequence: int


class Recorder:
    def __init__(self, node: Any, writer: BagWriter, selection: Selection, log: Any) -> None:
        """`node`: the recorder node's wire presence (raw subscriptions); `log`: its logger."""
        self.node = node
        self.writer = writer
        self.selection = selection
        self.log = log
        # Topics and samples go through one queue, so the writer thread alone touches the writer and a
        # topic is always registered before its first sample.
        self._queue: queue.Queue[_NewTopic | _Sample | None] = queue.Queue()
        self._subscribed: set[str] = set()
        self._skipped: set[str] = set()
        self._wake = threading.Event()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._write_loop, name="bag-writer", daemon=True)
        self._watcher = threading.Thread(target=self._watch_loop, name="bag-topics", daemon=True)
        self.started_ns = time.time_ns()

    def start(self) -> None:
        self._thread.start()
        self._watcher.start()
        # Graph events only wake the watcher: declaring subscriptions from inside a Zenoh callback could
        # deadlock the session.
        self.node.graph.add_listener(lambda event, ent: event == "put" and self._wake.set())
        self._wake.set()

    # ------------------------------------------------------------------ topics
    def _watch_loop(self) -> None:
        while not self._stop.is_set():
            self._wake.wait(1.0)
            self._wake.clear()
            if not self._stop.is_set():
                self._discover()

    def _discover(self) -> None:
        g = self.node.graph
        own = self.node.fqn
        for topic in sorted(g.topics()):
            if topic in self._subscribed or topic in self._skipped or not self.selection.wants(topic):
                continue
            pubs = [e for e in g.publishers(topic) if e.node_fqn != own]
            if not pubs:
                continue  # nobody publishes it (yet): its type is not offered
            kinds = sorted({e.type for e in pubs})
            if len(kinds) > 1:
                self._skip(topic, f"its publishers disagree on the type ({', '.join(kinds)})")
                continue
            typename = kinds[0]
            if not types.exists(typename):
                self._skip(topic, f"type {typename} is unknown here, so no schema can be written for it")
                continue
            self._subscribe(topic, typename, pubs)

    def _skip(self, topic: str, why: str) -> None:
        self._skipped.add(topic)
        self.log.warning(f"not recording {topic}: {why}")

    def _subscribe(self, topic: str, typename: str, pubs: list[Any]) -> None:
        offered = [qos_from_token(e.qos) for e in pubs]
        latched = any(q.durability == "transient_local" for q in offered)
        self._queue.put(_NewTopic(topic, typename, ros2msg(typename), tuple(offered),
                                  pubs[0].type_hash or types.type_hash(typename)))

        def on_sample(data: bytes, info: Any) -> None:
            self._queue.put(_Sample(topic, data, time.time_ns(), info.source_timestamp_ns, info.sequence_number))

        self.node.create_subscription(topic, typename, on_sample, raw=True, with_info=True, latched=latched,
                                      depth=max(q.depth for q in offered))
        self._subscribed.add(topic)
        self.log.info(f"Subscribed to topic '{topic}'")

    # ------------------------------------------------------------------ writing
    def _write_loop(self) -> None:
        last_flush = time.monotonic()
        while True:
            try:
                item = self._queue.get(timeout=FLUSH_PERIOD_S)
            except queue.Empty:
                item = _Idle
            if item is None:
                return
            if isinstance(item, _Sample):
                self.writer.write(item.topic, item.data, item.log_time_ns, item.publish_time_ns, item.sequence)
            elif isinstance(item, _NewTopic):
                self.writer.add_topic(item.topic, item.type, item.schema_text, qos=list(item.offered),
                                      type_hash=item.type_hash)
            if time.monotonic() - last_flush >= FLUSH_PERIOD_S:
                self.writer.flush()
                last_flush = time.monotonic()

    @property
    def subscribed(self) -> list[str]:
        return sorted(self._subscribed)

    def stop(self) -> Any:
        """Stop listening, write what was received, close the bag; returns its metadata."""
        self._stop.set()
        self._wake.set()
        self._watcher.join(5.0)
        self.node.close()
        self._queue.put(None)
        self._thread.join()
        return self.writer.close()
