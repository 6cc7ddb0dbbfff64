"""Writes a rosbag2 bag: `DIR/DIR_<n>.mcap` files as rosbag2_storage_mcap lays them out, and metadata.yaml.

The MCAP encoding is the `mcap` library's (chunked, indexed, summary with statistics): header profile
`ros2`, one `ros2msg` Schema per type, one `cdr` Channel per topic with `offered_qos_profiles` and
`topic_type_hash` metadata, Messages holding the CDR exactly as received, and the `rosbag2` Metadata
record. Files split by size or duration; `file` compression zstd-compresses each closed file, as rosbag2
does. Not thread-safe: the recorder calls it from one thread.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, replace
from pathlib import Path
from typing import IO

import yaml
import zstandard
from mcap.writer import CompressionType, Writer

from diffctl.bag.metadata import BagMetadata, FileInfo, Qos, TopicInfo, qos_list_to_yaml
from diffctl.bag.presets import MCAP_DEFAULT_CHUNK_BYTES, McapPreset
from diffctl.errors import ConfigError

CHUNK_COMPRESSION = {"none": CompressionType.NONE, "zstd": CompressionType.ZSTD, "lz4": CompressionType.LZ4}
DEFAULT_CHUNK_BYTES = MCAP_DEFAULT_CHUNK_BYTES


@dataclass(frozen=True)
class WriterOptions:
    """Validated options of `bag record` that shape the files."""

    max_bag_size_bytes: int = 0  # 0: never split by size
    max_bag_duration_s: float = 0.0  # 0: never split by time
    compression_mode: str = ""  # "" or "file"
    compression_format: str = ""  # "" or "zstd"
    chunk_compression: str = "none"  # MCAP chunk compression: none, zstd (storage presets), lz4 (tests' readers)
    chunk_size_bytes: int = DEFAULT_CHUNK_BYTES
    use_chunking: bool = True  # False: messages straight in the data section (the fastwrite preset)
    # The mcap Writer has one switch for the CRCs of chunks and of the summary: on, rosbag2's presets but
    # fastwrite get the summary CRC they ask for and chunk CRCs they leave out (a reader may check them or not).
    crcs: bool = True
    ros_distro: str = "jazzy"

    def __post_init__(self) -> None:
        if self.max_bag_size_bytes < 0:
            raise ConfigError(f"--max-bag-size {self.max_bag_size_bytes} must be 0 (no split) or a byte count")
        if self.max_bag_duration_s < 0:
            raise ConfigError(f"--max-bag-duration {self.max_bag_duration_s} must be 0 (no split) or seconds")
        if self.compression_mode not in ("", "file"):
            raise ConfigError(f"--compression-mode {self.compression_mode!r} is not supported with mcap storage",
                              hint="rosbag2 refuses message mode for MCAP too; use file, or "
                                   "--storage-preset-profile zstd_fast for compressed chunks")
        if self.compression_mode and self.compression_format != "zstd":
            raise ConfigError(f"--compression-format {self.compression_format!r} is not available",
                              hint="valid: zstd")
        if self.chunk_size_bytes <= 0:
            raise ConfigError(f"chunk size {self.chunk_size_bytes} must be a positive byte count")
        if self.chunk_compression not in CHUNK_COMPRESSION:
            raise ConfigError(f"chunk compression {self.chunk_compression!r} is not available",
                              hint="valid: " + ", ".join(CHUNK_COMPRESSION))


@dataclass
class _Topic:
    info: TopicInfo
    schema_encoding: str
    schema_text: str


@dataclass
class _File:
    path: Path
    stream: IO[bytes]
    writer: Writer
    channels: dict[str, int]
    first_ns: int | None = None
    last_ns: int = 0
    count: int = 0


class BagWriter:
    def __init__(self, bag_dir: Path, options: WriterOptions | None = None) -> None:
        self.dir = bag_dir
        self.options = options or WriterOptions()
        if bag_dir.exists():
            raise ConfigError(f"output folder {bag_dir} already exists", hint="choose another -o or remove it")
        try:
            bag_dir.mkdir(parents=True)
        except OSError as e:
            raise ConfigError(f"cannot create the bag folder {bag_dir}: {e.strerror}") from None
        self._topics: dict[str, _Topic] = {}
        self._counts: dict[str, int] = {}
        self._files: list[FileInfo] = []
        self._file: _File | None = None
        self._index = 0
        self._opened_at = time.monotonic()

    # ------------------------------------------------------------------ topics
    def add_topic(self, name: str, typename: str, schema_text: str, *, qos: list[Qos] | None = None,
                  type_hash: str = "", schema_encoding: str = "ros2msg") -> None:
        if name in self._topics:
            return
        self._topics[name] = _Topic(TopicInfo(name, typename, "cdr", tuple(qos or ()), type_hash),
                                    schema_encoding, schema_text)
        self._counts[name] = 0

    @property
    def topics(self) -> list[str]:
        return list(self._topics)

    def _channel(self, f: _File, topic: str) -> int:
        cid = f.channels.get(topic)
        if cid is None:
            t = self._topics[topic]
            schema_id = f.writer.register_schema(t.info.type, t.schema_encoding, t.schema_text.encode())
            metadata = {"offered_qos_profiles": qos_list_to_yaml(list(t.info.offered_qos_profiles))}
            if t.info.type_description_hash:
                metadata["topic_type_hash"] = t.info.type_description_hash
            cid = f.channels[topic] = f.writer.register_channel(topic, "cdr", schema_id, metadata)
        return cid

    # ------------------------------------------------------------------ files
    def _open_file(self) -> _File:
        path = self.dir / f"{self.dir.name}_{self._index}.mcap"
        self._index += 1
        stream = open(path, "wb")  # noqa: SIM115 — closed in _close_file
        o = self.options
        writer = Writer(stream, chunk_size=o.chunk_size_bytes, compression=CHUNK_COMPRESSION[o.chunk_compression],
                        use_chunking=o.use_chunking, enable_crcs=o.crcs)
        writer.start(profile="ros2", library="diffctl")
        self._opened_at = time.monotonic()
        return _File(path, stream, writer, {})

    def _close_file(self, f: _File, metadata: BagMetadata) -> None:
        # The `rosbag2` record: rosbag2 stores the bag's metadata (without the top key) in every file.
        body = yaml.safe_dump(metadata.to_dict()["rosbag2_bagfile_information"], sort_keys=False)
        f.writer.add_metadata("rosbag2", {"serialized_metadata": body})
        f.writer.finish()
        f.stream.flush()
        os.fsync(f.stream.fileno())
        f.stream.close()

    def _should_split(self, f: _File) -> bool:
        o = self.options
        if o.max_bag_size_bytes and f.count and f.stream.tell() >= o.max_bag_size_bytes:
            return True
        return bool(o.max_bag_duration_s and f.count
                    and time.monotonic() - self._opened_at >= o.max_bag_duration_s)

    def write(self, topic: str, cdr: bytes, log_time_ns: int, publish_time_ns: int = 0, sequence: int = 0) -> None:
        f = self._file
        if f is not None and self._should_split(f):
            self._finish_file(f)
            f = None
        if f is None:
            f = self._file = self._open_file()
        f.writer.add_message(self._channel(f, topic), log_time=log_time_ns, data=cdr,
                             publish_time=publish_time_ns or log_time_ns, sequence=sequence & 0xFFFFFFFF)
        f.first_ns = log_time_ns if f.first_ns is None else min(f.first_ns, log_time_ns)
        f.last_ns = max(f.last_ns, log_time_ns)
        f.count += 1
        self._counts[topic] += 1

    def flush(self) -> None:
        """Close the chunk in progress and hand every byte to the OS (what a killed recorder keeps)."""
        if self._file is not None:
            self._file.writer.flush()

    def _finish_file(self, f: _File) -> None:
        info = FileInfo(f.path.name, f.first_ns or 0, f.last_ns - (f.first_ns or f.last_ns), f.count)
        self._files.append(info)
        self._close_file(f, self.metadata())
        self._file = None

    # ------------------------------------------------------------------ the end
    def metadata(self) -> BagMetadata:
        files = list(self._files)
        spans = [(f.starting_time_ns, f.starting_time_ns + f.duration_ns) for f in files if f.message_count]
        cur = self._file
        if cur is not None and cur.count and cur.first_ns is not None:
            spans.append((cur.first_ns, cur.last_ns))
        start = min((s for s, _ in spans), default=0)
        end = max((e for _, e in spans), default=0)
        topics = tuple(replace(t.info, message_count=self._counts[n]) for n, t in self._topics.items())
        return BagMetadata(
            storage_identifier="mcap",
            relative_file_paths=tuple(f.path for f in files),
            starting_time_ns=start, duration_ns=max(0, end - start), message_count=sum(self._counts.values()),
            topics=topics, compression_format=self.options.compression_format,
            compression_mode=self.options.compression_mode.upper(), files=tuple(files),
            ros_distro=self.options.ros_distro,
        )

    def close(self) -> BagMetadata:
        """Finish the open file, compress files if asked, write metadata.yaml; returns what it wrote."""
        if self._file is None and not self._files:
            self._file = self._open_file()  # an empty bag is still a valid bag, with one empty file
        if self._file is not None:
            self._finish_file(self._file)
        if self.options.compression_mode == "file":
            self._files = [self._compress(f) for f in self._files]
        meta = self.metadata()
        meta.write(self.dir)
        return meta

    def _compress(self, f: FileInfo) -> FileInfo:
        src = self.dir / f.path
        dst = src.with_name(src.name + ".zstd")
        with open(src, "rb") as i, open(dst, "wb") as o:
            zstandard.ZstdCompressor().copy_stream(i, o)
        src.unlink()
        return replace(f, path=dst.name)


def preset_options(preset: McapPreset, **options: object) -> WriterOptions:
    """WriterOptions shaping the files as rosbag2's MCAP plugin does with this storage preset."""
    return WriterOptions(chunk_compression=preset.compression, chunk_size_bytes=preset.chunk_size_bytes,
                         use_chunking=preset.use_chunking, crcs=preset.summary_crc, **options)  # type: ignore[arg-type]
