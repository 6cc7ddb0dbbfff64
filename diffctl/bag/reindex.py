"""`bag reindex`: make a bag whole again after its recorder was killed.

rosbag2's reindex rebuilds metadata.yaml from the storage files. A recorder killed with SIGKILL also
leaves its last MCAP file without summary and footer (and without the chunk it was filling), which no
reader opens; so files that do not end in a footer are first rewritten from every record that was
completely written, with the `mcap` library doing both the tolerant reading and the writing.
"""

from __future__ import annotations

from pathlib import Path

from mcap.exceptions import McapError
from mcap.records import Channel, Message, Schema
from mcap.stream_reader import StreamReader
from mcap.writer import CompressionType, Writer

from diffctl.bag.reader import Bag, has_footer
from diffctl.errors import ConfigError


def salvage(path: Path) -> int:
    """Rewrite `path` from its complete records; returns how many messages survived."""
    schemas: dict[int, Schema] = {}
    channels: dict[int, Channel] = {}
    messages: list[Message] = []
    profile = "ros2"
    with open(path, "rb") as f:
        try:
            for rec in StreamReader(f).records:
                if isinstance(rec, Schema):
                    schemas[rec.id] = rec
                elif isinstance(rec, Channel):
                    channels[rec.id] = rec
                elif isinstance(rec, Message):
                    messages.append(rec)
                elif getattr(rec, "profile", None) is not None:
                    profile = rec.profile  # the Header record
        except (McapError, EOFError, ValueError, KeyError, AssertionError):
            pass  # the first incomplete record: everything before it is kept
    tmp = path.with_name(path.name + ".reindex")
    with open(tmp, "wb") as out:
        w = Writer(out, compression=CompressionType.NONE)
        w.start(profile=profile, library="diffctl reindex")
        schema_ids = {sid: w.register_schema(s.name, s.encoding, s.data) for sid, s in schemas.items()}
        channel_ids = {cid: w.register_channel(c.topic, c.message_encoding, schema_ids.get(c.schema_id, 0),
                                               dict(c.metadata))
                       for cid, c in channels.items()}
        kept = 0
        for m in sorted(messages, key=lambda m: m.log_time):
            if m.channel_id in channel_ids:
                w.add_message(channel_ids[m.channel_id], m.log_time, m.data, m.publish_time, m.sequence)
                kept += 1
        w.finish()
    tmp.replace(path)
    return kept


def reindex(bag_dir: Path) -> tuple[list[str], int]:
    """Repair unfinished files, rewrite metadata.yaml; returns (repaired file names, messages in the bag)."""
    if not bag_dir.is_dir():
        raise ConfigError(f"{bag_dir} is not a bag folder", hint="reindex takes the folder a recorder wrote")
    files = sorted(bag_dir.glob("*.mcap"), key=lambda p: (len(p.name), p.name))
    if not files:
        raise ConfigError(f"{bag_dir} holds no .mcap files", hint="is it a bag folder?")
    repaired = []
    for p in files:
        if not has_footer(p):
            salvage(p)
            repaired.append(p.name)
    meta_path = bag_dir / "metadata.yaml"
    if meta_path.exists():
        meta_path.unlink()  # rebuilt below from the files alone, as rosbag2's reindex does
    bag = Bag(bag_dir)
    try:
        meta = bag.metadata
        meta.write(bag_dir)
        return repaired, meta.message_count
    finally:
        bag.close()
