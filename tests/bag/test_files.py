"""Bags on disk, no bus: diffctl's writer read back by the independent `mcap` reader (and mcap-ros2-support's
decoder), bags written by rosbags and by the mcap library read by `bag info`, and bad bags refused."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from mcap.reader import make_reader
from mcap.writer import CompressionType
from mcap_ros2.decoder import DecoderFactory

from diffctl.bag.metadata import Qos, parse
from diffctl.bag.msgdefs import ros2msg
from diffctl.bag.reader import Bag
from diffctl.bag.writer import BagWriter, WriterOptions
from diffctl.errors import ConfigError
from diffctl.interfaces import types
from tests.bag.fixtures import BASIC, T0, downgrade, mcap_file, rosbags_bag

ODOM = "nav_msgs/msg/Odometry"


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "diffctl", *args], capture_output=True, text=True, timeout=120)


def write_bag(path: Path, n: int = 25, **opts) -> None:
    w = BagWriter(path, WriterOptions(**opts))
    w.add_topic("/odom", ODOM, ros2msg(ODOM), qos=[Qos(depth=5)], type_hash=types.type_hash(ODOM))
    for i in range(n):
        m = types.new(ODOM, {"header": {"frame_id": "odom"}, "pose": {"pose": {"position": {"x": 0.25 * i}}}})
        w.write("/odom", types.serialize(m, ODOM), T0 + i * 10_000_000, T0 + i * 10_000_000 - 5, i + 1)
    w.close()


def topic_counts(info_text: str) -> dict[str, int]:
    out = {}
    for line in info_text.splitlines():
        if "Topic: " in line:
            fields = dict(part.strip().split(": ", 1) for part in line.split("Topic information:")[-1].split("|"))
            out[fields["Topic"]] = int(fields["Count"])
    return out


@pytest.mark.parametrize("chunks", ["none", "zstd", "lz4"])
def test_diffctl_bag_is_read_by_the_mcap_library(tmp_path: Path, chunks: str) -> None:
    bag = tmp_path / "b"
    write_bag(bag, chunk_compression=chunks)
    meta = yaml.safe_load((bag / "metadata.yaml").read_text())["rosbag2_bagfile_information"]
    assert meta["version"] == 9 and meta["relative_file_paths"] == ["b_0.mcap"]
    assert meta["topics_with_message_count"][0]["topic_metadata"]["offered_qos_profiles"][0]["depth"] == 5
    with open(bag / "b_0.mcap", "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        assert reader.get_header().profile == "ros2"
        summary = reader.get_summary()
        assert summary.chunk_indexes and all(c.compression == ("" if chunks == "none" else chunks)
                                             for c in summary.chunk_indexes)
        got = list(reader.iter_decoded_messages())
    assert len(got) == 25
    schema, channel, message, decoded = got[3]
    assert (schema.name, schema.encoding, channel.message_encoding) == (ODOM, "ros2msg", "cdr")
    assert "\n" + "=" * 80 + "\nMSG: std_msgs/Header\n" in schema.data.decode()
    assert channel.metadata["topic_type_hash"] == types.type_hash(ODOM)
    assert yaml.safe_load(channel.metadata["offered_qos_profiles"])[0]["reliability"] == "reliable"
    assert decoded.pose.pose.position.x == pytest.approx(0.75)
    assert (message.log_time, message.publish_time, message.sequence) == (T0 + 30_000_000, T0 + 29_999_995, 4)


def test_splits_and_file_compression(tmp_path: Path) -> None:
    bag = tmp_path / "split"
    write_bag(bag, n=400, max_bag_size_bytes=20_000, chunk_size_bytes=4096, compression_mode="file",
              compression_format="zstd")
    b = Bag(bag)
    try:
        names = b.metadata.relative_file_paths
        assert len(names) > 1 and names[0] == "split_0.mcap.zstd" and b.metadata.compression_mode == "FILE"
        assert sum(f.message_count for f in b.metadata.files) == 400 == len(list(b.messages()))
    finally:
        b.close()
    out = run("bag", "info", str(bag))
    assert out.returncode == 0, out.stderr
    assert topic_counts(out.stdout) == {"/odom": 400}


@pytest.mark.parametrize("version", [4, 5, 6, 7, 8, 9])
def test_info_reads_rosbags_bags_of_every_metadata_version(tmp_path: Path, version: int) -> None:
    bag = tmp_path / f"v{version}"
    counts = rosbags_bag(bag, version=9 if version == 9 else 8)
    if version < 8:
        downgrade(bag, version)
    out = run("bag", "info", str(bag))
    assert out.returncode == 0, out.stderr
    assert topic_counts(out.stdout) == counts
    assert f"Messages:          {sum(counts.values())}" in out.stdout
    assert "Type: test_msgs/msg/BasicTypes" in out.stdout


@pytest.mark.parametrize("compression", [CompressionType.ZSTD, CompressionType.LZ4])
def test_info_of_a_bare_mcap_and_of_a_folder_without_metadata(tmp_path: Path, compression) -> None:
    d = tmp_path / "nometa"
    d.mkdir()
    n = mcap_file(d / "nometa_0.mcap", compression)
    for target in (d, d / "nometa_0.mcap"):
        out = run("bag", "info", str(target))
        assert out.returncode == 0, out.stderr
        assert topic_counts(out.stdout) == {"/cmd_vel": n}
        assert "Duration:          1.450000000s" in out.stdout


def test_a_type_unknown_to_diffctl_is_learnt_from_the_bag(tmp_path: Path) -> None:
    bag = tmp_path / "basic"
    rosbags_bag(bag, version=8)
    assert not types.exists(BASIC)
    from diffctl.bag.bus_side import plan_topics

    b = Bag(bag)
    try:
        played = plan_topics(b, ("/basic",), {}, set())
        assert [p.type for p in played] == [BASIC] and types.exists(BASIC)
        first = next(m for m in b.messages({"/basic"}))
        msg = types.deserialize(first.data, BASIC)
        assert (msg.int64_value, msg.uint64_value, msg.char_value) == (-(2**40), 2**50, 65)
    finally:
        b.close()


def one_error_line(out: subprocess.CompletedProcess) -> str:
    assert out.returncode == 2, (out.stdout, out.stderr)
    lines = [ln for ln in out.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: "), out.stderr
    return lines[0]


def test_truncated_mcap_is_refused_in_one_line(tmp_path: Path) -> None:
    bag = tmp_path / "cut"
    write_bag(bag, n=200)
    f = bag / "cut_0.mcap"
    f.write_bytes(f.read_bytes()[: f.stat().st_size // 2])
    for cmd in ("info", "play"):
        line = one_error_line(run("bag", cmd, str(bag)))
        assert "cut_0.mcap" in line and "truncated" in line and "reindex" in line


def test_metadata_that_lies_about_its_files(tmp_path: Path) -> None:
    bag = tmp_path / "liar"
    write_bag(bag)
    meta = bag / "metadata.yaml"
    doc = yaml.safe_load(meta.read_text())
    doc["rosbag2_bagfile_information"]["relative_file_paths"] = ["liar_0.mcap", "liar_1.mcap"]
    meta.write_text(yaml.safe_dump(doc))
    line = one_error_line(run("bag", "play", str(bag)))
    assert "metadata.yaml" in line and "liar_1.mcap" in line and "present: liar_0.mcap" in line
    doc["rosbag2_bagfile_information"]["relative_file_paths"] = ["liar_0.mcap"]
    doc["rosbag2_bagfile_information"]["files"][0]["message_count"] = 99
    meta.write_text(yaml.safe_dump(doc))
    line = one_error_line(run("bag", "info", str(bag)))
    assert "99 messages" in line and "holds 25" in line


def test_unknown_compression_is_refused(tmp_path: Path) -> None:
    bag = tmp_path / "comp"
    write_bag(bag)
    meta = bag / "metadata.yaml"
    doc = yaml.safe_load(meta.read_text())
    doc["rosbag2_bagfile_information"].update(compression_format="bz2", compression_mode="FILE")
    meta.write_text(yaml.safe_dump(doc))
    line = one_error_line(run("bag", "play", str(bag)))
    assert "compression_format" in line and "'bz2'" in line


def test_metadata_missing_a_key_of_its_version(tmp_path: Path) -> None:
    bag = tmp_path / "v5"
    rosbags_bag(bag, version=8)
    downgrade(bag, 5)
    doc = yaml.safe_load((bag / "metadata.yaml").read_text())
    del doc["rosbag2_bagfile_information"]["files"]
    with pytest.raises(ConfigError, match="missing key 'files'"):
        parse(yaml.safe_dump(doc), "metadata.yaml")


def test_reindex_recovers_a_bag_whose_writer_never_finished(tmp_path: Path) -> None:
    bag = tmp_path / "killed"
    w = BagWriter(bag, WriterOptions(chunk_size_bytes=2048))
    w.add_topic("/odom", ODOM, ros2msg(ODOM), type_hash=types.type_hash(ODOM))
    for i in range(100):
        m = types.new(ODOM, {"pose": {"pose": {"position": {"x": float(i)}}}})
        w.write("/odom", types.serialize(m, ODOM), T0 + i * 1000, 0, i + 1)
    w.flush()  # what the recorder does every second; the process then dies without closing
    one_error_line(run("bag", "info", str(bag)))
    out = run("bag", "reindex", str(bag))
    assert out.returncode == 0, out.stderr
    out = run("bag", "info", str(bag))
    assert out.returncode == 0 and topic_counts(out.stdout) == {"/odom": 100}


@pytest.mark.parametrize("mode", ["FILE", "MESSAGE"])
def test_rosbags_file_and_message_compression_are_read(tmp_path: Path, mode: str) -> None:
    from rosbags.rosbag2 import StoragePlugin
    from rosbags.rosbag2 import Writer as RosbagsWriter
    from rosbags.rosbag2.enums import CompressionFormat, CompressionMode
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS2_JAZZY)
    path = tmp_path / mode.lower()
    w = RosbagsWriter(path, version=8, storage_plugin=StoragePlugin.MCAP)
    w.set_compression(CompressionMode[mode], CompressionFormat.ZSTD)
    w.open()
    conn = w.add_connection("/chatter", "std_msgs/msg/String", typestore=ts)
    for i in range(5):
        w.write(conn, T0 + i, ts.serialize_cdr(ts.types["std_msgs/msg/String"](data=f"x{i}"), "std_msgs/msg/String"))
    w.close()
    b = Bag(path)
    try:
        assert b.metadata.compression_mode.upper() == mode
        assert [types.deserialize(m.data, "std_msgs/msg/String").data for m in b.messages()] == \
            [f"x{i}" for i in range(5)]
    finally:
        b.close()


def test_unknown_chunk_compression_is_refused(tmp_path: Path) -> None:
    bag = tmp_path / "chunks"
    write_bag(bag, chunk_compression="zstd")
    f = bag / "chunks_0.mcap"
    raw = f.read_bytes()
    # The compression name is stored length-prefixed in every Chunk and Chunk Index record: rename it in
    # place (same length, offsets unchanged) to a compression no reader knows.
    f.write_bytes(raw.replace(b"\x04\x00\x00\x00zstd", b"\x04\x00\x00\x00zzzz"))
    line = one_error_line(run("bag", "play", str(bag)))
    assert "chunks_0.mcap" in line and "'zzzz'" in line and "readable: none, zstd, lz4" in line


def test_split_by_duration(tmp_path: Path) -> None:
    import time

    bag = tmp_path / "dur"
    w = BagWriter(bag, WriterOptions(max_bag_duration_s=0.2))
    w.add_topic("/odom", ODOM, ros2msg(ODOM))
    cdr = types.serialize(types.new(ODOM, {}), ODOM)
    w.write("/odom", cdr, T0)
    time.sleep(0.3)  # the first file is now older than --max-bag-duration
    w.write("/odom", cdr, T0 + 1)
    meta = w.close()
    assert meta.relative_file_paths == ("dur_0.mcap", "dur_1.mcap")
    assert [f.message_count for f in meta.files] == [1, 1]
    assert topic_counts(run("bag", "info", str(bag)).stdout) == {"/odom": 2}


STRING = "std_msgs/msg/String"


@pytest.mark.parametrize("name", ["none", "fastwrite", "zstd_fast", "zstd_small"])
def test_storage_presets_shape_the_file_as_rosbag2s_mcap_plugin(tmp_path: Path, name: str) -> None:
    from mcap.records import Chunk, Footer, Message
    from mcap.stream_reader import StreamReader

    from diffctl.bag.presets import preset
    from diffctl.bag.writer import preset_options

    bag = tmp_path / name
    w = BagWriter(bag, preset_options(preset(name)))
    w.add_topic("/text", STRING, ros2msg(STRING), qos=[Qos(depth=10)], type_hash=types.type_hash(STRING))
    n, size = 300, 8000  # 2.4 MB of text: several 768 KiB chunks, one 4 MiB chunk
    for i in range(n):
        text = (f"{i:06d} " * (size // 7 + 1))[:size]
        w.write("/text", types.serialize(types.new(STRING, {"data": text}), STRING), T0 + i * 1000, T0 + i * 1000, i)
    w.close()

    # The file as the mcap package's own reader sees it, record by record.
    with open(bag / f"{name}_0.mcap", "rb") as f:
        records = list(StreamReader(f, emit_chunks=True, validate_crcs=True).records)
    chunks = [r for r in records if isinstance(r, Chunk)]
    footer = next(r for r in records if isinstance(r, Footer))
    direct = [r for r in records if isinstance(r, Message)]
    if name == "fastwrite":
        assert chunks == [] and len(direct) == n  # no chunking: messages straight in the data section
        assert footer.summary_crc == 0  # rosbag2: noSummaryCRC
    else:
        assert direct == [] and footer.summary_crc != 0
        limit = 4 * 1024 * 1024 if name == "zstd_small" else 768 * 1024
        assert all(c.uncompressed_size <= limit + size + 64 for c in chunks)
        assert len(chunks) == (1 if name == "zstd_small" else 4)
        want = "zstd" if name.startswith("zstd") else ""
        assert {c.compression for c in chunks} == {want}
        if want:
            assert sum(len(c.data) for c in chunks) < n * size / 10  # repetitive text compresses
    # …and read back through the summary by mcap's indexed reader, and by diffctl's own.
    with open(bag / f"{name}_0.mcap", "rb") as f:
        got = [m.sequence for _, _, m in make_reader(f).iter_messages()]
    assert got == list(range(n))
    b = Bag(bag)
    assert [m.sequence for m in b.messages()] == list(range(n))
    b.close()


def test_an_unknown_storage_preset_is_refused_with_the_valid_ones(tmp_path: Path) -> None:
    done = run("bag", "record", "-a", "-o", str(tmp_path / "b"), "--storage-preset-profile", "lz4")
    assert done.returncode == 2
    assert "'lz4' is not an MCAP storage preset" in done.stderr
    assert "valid: none, fastwrite, zstd_fast, zstd_small" in done.stderr
    assert not (tmp_path / "b").exists()
    done = run("bag", "record", "-a", "-o", str(tmp_path / "b"), "--storage-preset-profile", "zstd_smal")
    assert done.returncode == 2 and "did you mean 'zstd_small'?" in done.stderr
