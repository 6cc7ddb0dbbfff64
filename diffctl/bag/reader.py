"""Opens rosbag2 bags (a folder with metadata.yaml, a folder without it, or one `.mcap` file) and checks
them completely before anything is read out: files exist, every MCAP file is whole (magic, footer,
summary), every chunk's compression is one we can read. A bad bag is one ConfigError, never half a replay.

MCAP records are decoded by the `mcap` library; this module only maps them to topics and rosbag2 metadata.
"""

from __future__ import annotations

import heapq
import shutil
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import zstandard
from mcap import records as mcap_records
from mcap.exceptions import McapError
from mcap.reader import FOOTER_SIZE, make_reader
from mcap.records import Chunk, Footer
from mcap.stream_reader import StreamReader

from diffctl.bag.metadata import BagMetadata, FileInfo, Qos, TopicInfo, load, qos_list_from
from diffctl.errors import ConfigError

MAGIC = b"\x89MCAP0\r\n"
CHUNK_COMPRESSIONS = ("", "zstd", "lz4")
FILE_COMPRESSIONS = ("", "zstd")


@dataclass(frozen=True)
class Channel:
    topic: str
    type: str
    message_encoding: str
    schema_encoding: str
    schema_text: str
    qos: tuple[Qos, ...] = ()
    type_hash: str = ""


@dataclass
class McapFile:
    """One MCAP file's channels and statistics, from its summary (or a scan when it has none)."""

    path: Path
    channels: dict[int, Channel] = field(default_factory=dict)
    counts: dict[int, int] = field(default_factory=dict)
    start_ns: int = 0
    end_ns: int = 0
    profile: str = ""

    @property
    def message_count(self) -> int:
        return sum(self.counts.values())


@dataclass(frozen=True)
class Message:
    topic: str
    log_time_ns: int
    publish_time_ns: int
    sequence: int
    data: bytes


def _channel(ch: mcap_records.Channel, schema: mcap_records.Schema | None, where: str) -> Channel:
    meta = dict(ch.metadata or {})
    qos = tuple(qos_list_from(meta.get("offered_qos_profiles", ""), f"{where}: channel {ch.topic}"))
    type_hash = meta.get("topic_type_hash", "")
    if schema is None:
        return Channel(ch.topic, "", ch.message_encoding, "", "", qos, type_hash)
    return Channel(ch.topic, schema.name, ch.message_encoding, schema.encoding,
                   bytes(schema.data).decode("utf-8", "replace"), qos, type_hash)


def _fail(path: Path, what: str) -> ConfigError:
    return ConfigError(what, source=str(path),
                       hint="if a recorder was killed, `diffctl bag reindex DIR` recovers every complete chunk")


def open_mcap(path: Path) -> McapFile:
    """Check one MCAP file end to end and read its summary."""
    try:
        size = path.stat().st_size
        with open(path, "rb") as f:
            head = f.read(len(MAGIC))
            if head != MAGIC:
                raise ConfigError("not an MCAP file (bad magic at its start)", source=str(path))
            if size < 2 * len(MAGIC) + 20:
                raise _fail(path, f"truncated MCAP ({size} bytes, no footer)")
            f.seek(-len(MAGIC), 2)
            if f.read(len(MAGIC)) != MAGIC:
                raise _fail(path, f"truncated MCAP: no closing magic at byte {size} (the file ends mid-record)")
            f.seek(0)
            reader = make_reader(f)
            header = reader.get_header()
            summary = reader.get_summary()
            out = McapFile(path, profile=header.profile)
            if summary is None:
                return _scan(path, out)
            for ci in summary.chunk_indexes:
                if ci.compression not in CHUNK_COMPRESSIONS:
                    raise ConfigError(f"chunk at byte {ci.chunk_start_offset} uses compression {ci.compression!r}",
                                      source=str(path), hint="readable: none, zstd, lz4")
            for cid, ch in summary.channels.items():
                out.channels[cid] = _channel(ch, summary.schemas.get(ch.schema_id), str(path))
            st = summary.statistics
            if st is not None:
                out.counts = {cid: st.channel_message_counts.get(cid, 0) for cid in out.channels}
                out.start_ns, out.end_ns = (st.message_start_time, st.message_end_time) if st.message_count else (0, 0)
                return out
            return _scan(path, out)
    except ConfigError:
        raise
    except OSError as e:
        raise ConfigError(f"cannot read the bag file: {e.strerror}", source=str(path)) from None
    except (McapError, ValueError, KeyError, EOFError) as e:
        raise _fail(path, f"damaged MCAP: {type(e).__name__}: {e}") from None


def _scan(path: Path, out: McapFile) -> McapFile:
    """Statistics the hard way, for files written without a summary section."""
    with open(path, "rb") as f:
        for rec in StreamReader(f, emit_chunks=True).records:
            if isinstance(rec, Chunk) and rec.compression not in CHUNK_COMPRESSIONS:
                raise ConfigError(f"a chunk uses compression {rec.compression!r}", source=str(path),
                                  hint="readable: none, zstd, lz4")
    times: list[int] = []
    with open(path, "rb") as f:
        for schema, ch, msg in make_reader(f).iter_messages(log_time_order=False):
            out.channels.setdefault(ch.id, _channel(ch, schema, str(path)))
            out.counts[ch.id] = out.counts.get(ch.id, 0) + 1
            times.append(msg.log_time)
    out.start_ns, out.end_ns = (min(times), max(times)) if times else (0, 0)
    return out


class Bag:
    """A checked bag: its metadata (read, or derived from the MCAP summaries) and its files."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self._tmp: Path | None = None
        try:
            self._open()
        except BaseException:
            self.close()  # a refused bag leaves no decompressed copies behind
            raise

    def _open(self) -> None:
        path = self.path
        if not path.exists():
            raise ConfigError(f"no bag at {path}", hint="give a bag folder or an .mcap file")
        meta_path = path / "metadata.yaml" if path.is_dir() else None
        self.has_metadata = bool(meta_path and meta_path.is_file())
        meta: BagMetadata | None = None
        if meta_path is not None and self.has_metadata:
            meta = load(meta_path)
            self.file_paths = self._files_from_metadata(meta, str(meta_path))
        elif path.is_dir():
            self.file_paths = sorted(path.glob("*.mcap"))
            if not self.file_paths:
                raise ConfigError(f"{path} holds neither metadata.yaml nor .mcap files", hint="is it a bag folder?")
        else:
            self.file_paths = [path]
        self.files = [open_mcap(p) for p in self.file_paths]
        self.message_compressed = meta is not None and meta.compression_mode.upper() == "MESSAGE"
        self.metadata = meta if meta is not None else self._derive()
        if meta is not None:
            self._check_against_files(str(meta_path))

    def _files_from_metadata(self, meta: BagMetadata, source: str) -> list[Path]:
        if meta.storage_identifier != "mcap":
            raise ConfigError(f"storage {meta.storage_identifier!r} is not readable here", source=source,
                              field="storage_identifier", hint="diffctl reads mcap bags")
        if meta.compression_format not in FILE_COMPRESSIONS:
            raise ConfigError(f"unknown compression format {meta.compression_format!r}", source=source,
                              field="compression_format", hint="readable: zstd (or none)")
        if meta.compression_mode.upper() not in ("", "NONE", "FILE", "MESSAGE"):
            raise ConfigError(f"unknown compression mode {meta.compression_mode!r}", source=source,
                              field="compression_mode", hint="valid: FILE, MESSAGE or empty")
        if not meta.relative_file_paths:
            raise ConfigError("the bag lists no files", source=source, field="relative_file_paths")
        paths = []
        for name in meta.relative_file_paths:
            p = self.path / name
            if not p.is_file() and (self.path / Path(name).name).is_file():
                p = self.path / Path(name).name  # Foxy-era bags list `<bag dir>/<file>`
            if not p.is_file():
                present = ", ".join(sorted(q.name for q in self.path.iterdir() if q.name != "metadata.yaml"))
                raise ConfigError(f"lists {name} but the bag folder has no such file", source=source,
                                  field="relative_file_paths", hint=f"present: {present or '(nothing)'}")
            if meta.compression_mode.upper() == "FILE":
                p = self._decompress(p, source)
            paths.append(p)
        return paths

    def _decompress(self, p: Path, source: str) -> Path:
        if self._tmp is None:
            self._tmp = Path(tempfile.mkdtemp(prefix="diffctl-bag-"))
        out = self._tmp / (p.name[:-5] if p.name.endswith(".zstd") else p.name)
        try:
            with open(p, "rb") as i, open(out, "wb") as o:
                zstandard.ZstdDecompressor().copy_stream(i, o)
        except zstandard.ZstdError as e:
            raise ConfigError(f"{p.name} is not a zstd file although the bag says FILE compression: {e}",
                              source=source, field="compression_mode") from None
        return out

    def _check_against_files(self, source: str) -> None:
        meta = self.metadata
        for fi, mf in zip(meta.files, self.files, strict=False):
            if fi.message_count != mf.message_count:
                raise ConfigError(f"says {fi.path} holds {fi.message_count} messages but it holds "
                                  f"{mf.message_count}", source=source, field="files",
                                  hint="`diffctl bag reindex DIR` rewrites metadata.yaml from the files")
        total = sum(f.message_count for f in self.files)
        if meta.message_count != total:
            raise ConfigError(f"says the bag holds {meta.message_count} messages but its files hold {total}",
                              source=source, field="message_count",
                              hint="`diffctl bag reindex DIR` rewrites metadata.yaml from the files")

    def _derive(self) -> BagMetadata:
        topics: dict[str, TopicInfo] = {}
        infos = []
        for mf in self.files:
            for cid, ch in mf.channels.items():
                prev = topics.get(ch.topic)
                n = mf.counts.get(cid, 0) + (prev.message_count if prev else 0)
                topics[ch.topic] = TopicInfo(ch.topic, ch.type, ch.message_encoding, ch.qos, ch.type_hash, n)
            infos.append(FileInfo(mf.path.name, mf.start_ns, mf.end_ns - mf.start_ns, mf.message_count))
        spans = [(f.start_ns, f.end_ns) for f in self.files if f.message_count]
        start = min((s for s, _ in spans), default=0)
        end = max((e for _, e in spans), default=0)
        return BagMetadata(storage_identifier="mcap", relative_file_paths=tuple(i.path for i in infos),
                           starting_time_ns=start, duration_ns=end - start,
                           message_count=sum(t.message_count for t in topics.values()),
                           topics=tuple(topics.values()), files=tuple(infos))

    # ------------------------------------------------------------------ content
    def channels(self) -> dict[str, Channel]:
        """Topic → its channel (the first file's, when a topic appears in several)."""
        out: dict[str, Channel] = {}
        for mf in self.files:
            for ch in mf.channels.values():
                out.setdefault(ch.topic, ch)
        return out

    @property
    def size_bytes(self) -> int:
        if self.path.is_dir():
            return sum(p.stat().st_size for p in self.path.iterdir() if p.is_file())
        return self.path.stat().st_size

    def messages(self, topics: set[str] | None = None, start_ns: int | None = None) -> Iterator[Message]:
        """Every message (of `topics`, from `start_ns`) in log-time order across all files."""
        streams = [self._file_messages(mf.path, topics, start_ns) for mf in self.files]
        yield from heapq.merge(*streams, key=lambda m: m.log_time_ns)

    def _file_messages(self, path: Path, topics: set[str] | None, start_ns: int | None) -> Iterator[Message]:
        unzstd = zstandard.ZstdDecompressor() if self.message_compressed else None
        with open(path, "rb") as f:
            reader = make_reader(f)
            for _, ch, msg in reader.iter_messages(topics=sorted(topics) if topics is not None else None,
                                                   start_time=start_ns, log_time_order=True):
                data = msg.data if unzstd is None else unzstd.decompress(msg.data)
                yield Message(ch.topic, msg.log_time, msg.publish_time, msg.sequence, bytes(data))

    def close(self) -> None:
        if self._tmp is not None:
            shutil.rmtree(self._tmp, ignore_errors=True)
            self._tmp = None


def has_footer(path: Path) -> bool:
    """Whether a file ends in a footer and magic (a cleanly closed MCAP)."""
    try:
        with open(path, "rb") as f:
            f.seek(-len(MAGIC), 2)
            if f.read(len(MAGIC)) != MAGIC:
                return False
            f.seek(-(len(MAGIC) + FOOTER_SIZE), 2)
            return isinstance(next(StreamReader(f, skip_magic=True).records), Footer)
    except (OSError, McapError, StopIteration, ValueError):
        return False
