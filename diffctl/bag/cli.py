"""`diffctl bag record|info|play|reindex`: the `ros2 bag` counterpart, writing and reading rosbag2 MCAP bags."""

from __future__ import annotations

import os
import threading
import time
from pathlib import Path
from typing import Any

import click

from diffctl.console import console, info
from diffctl.errors import ConfigError
from diffctl.signals import stop_on_signals


@click.group()
def bag() -> None:
    """Record and replay topics in rosbag2 bags (MCAP), as `ros2 bag` does.

    \b
    Example:
      diffctl bag record -a -o run1
      diffctl bag info run1
      diffctl bag play run1 --clock
    """


def default_output() -> Path:
    # rosbag2's default name. Started by `diffctl launch`, the recorder writes next to the run's logs.
    name = time.strftime("rosbag2_%Y_%m_%d-%H_%M_%S")
    base = os.environ.get("DIFFCTL_LOG_DIR")
    return Path(base) / name if base else Path(name)


@bag.command()
@click.argument("topic_args", nargs=-1, metavar="[TOPIC]...")
@click.option("-a", "--all", "all_", is_flag=True, help="Record every topic (hidden: with --include-hidden-topics).")
@click.option("--all-topics", is_flag=True, help="Same as --all (services are not recorded).")
@click.option("--topics", "topics_opt", multiple=True, help="A topic to record (repeatable).")
@click.option("-e", "--regex", default="", help="Record topics matching this regular expression.")
@click.option("--exclude-regex", "--exclude", "exclude", default="", help="Leave out topics matching this expression.")
@click.option("--include-hidden-topics", is_flag=True, help="With --all, record hidden topics too.")
@click.option("-o", "--output", type=click.Path(path_type=Path), default=None,
              help="Bag folder to create (default rosbag2_<date>-<time>).")
@click.option("-s", "--storage", default="mcap", help="Storage format (mcap).")
@click.option("-b", "--max-bag-size", type=int, default=0, help="Split files at this many bytes (0: never).")
@click.option("-d", "--max-bag-duration", type=float, default=0.0, help="Split files after this many seconds.")
@click.option("--compression-mode", type=click.Choice(["none", "file", "message"]), default="none",
              help="Compress each closed file (file).")
@click.option("--compression-format", default="", help="Compression format (zstd).")
@click.option("--storage-preset-profile", default="", help="MCAP preset: none, fastwrite, zstd_fast, zstd_small.")
def record(topic_args: tuple[str, ...], all_: bool, all_topics: bool, topics_opt: tuple[str, ...], regex: str,
           exclude: str, include_hidden_topics: bool, output: Path | None, storage: str, max_bag_size: int,
           max_bag_duration: float, compression_mode: str, compression_format: str,
           storage_preset_profile: str) -> None:
    """Record topics into a bag folder until Ctrl-C.

    \b
    Example:
      diffctl bag record -a -o run1
      diffctl bag record /diffbot_base_controller/odom /tf --compression-mode file --compression-format zstd
    """
    from diffctl.bag.presets import preset
    from diffctl.bag.recorder import Recorder, Selection
    from diffctl.bag.writer import BagWriter, preset_options

    if storage != "mcap":
        raise ConfigError(f"--storage {storage!r} is not available", hint="valid: mcap")
    chosen = preset(storage_preset_profile)
    topics = tuple("/" + t.lstrip("/") for t in (*topic_args, *topics_opt))
    selection = Selection(all_topics=all_ or all_topics, topics=topics, regex=regex, exclude_regex=exclude,
                          include_hidden=include_hidden_topics)
    mode = "" if compression_mode == "none" else compression_mode
    options = preset_options(chosen, max_bag_size_bytes=max_bag_size, max_bag_duration_s=max_bag_duration,
                             compression_mode=mode, compression_format=compression_format if mode else "")
    out = output or default_output()
    if out.exists():
        raise ConfigError(f"output folder {out} already exists", hint="choose another -o or remove it")
    stop = stop_on_signals()
    # rosbag2_py's recorder node: no /parameter_events publisher (rosbag2 turns it off), rclcpp's parameters.
    node = _start_node("rosbag2_recorder", start_parameter_event_publisher=False)
    log = node.node.get_logger()
    writer = BagWriter(out, options)
    # Recording is a hot path: raw subscriptions on the node's wire presence, beside the client Node.
    recorder = Recorder(node.node.bus_node, writer, selection, log)
    log.info("Listening for topics...")
    recorder.start()
    log.info(f"Recording to {out}... (Ctrl-C stops and closes the bag)")
    started = time.monotonic()
    stop.wait()
    meta = recorder.stop()
    log.info("Recording stopped")
    log.info(f"Wrote {meta.message_count} messages on {len(meta.topics)} topics in "
             f"{time.monotonic() - started:.1f} s to {out}")
    node.stop()


def _start_node(name: str, **options: Any) -> Any:
    from diffctl.client import component
    from diffctl.client.node import Node

    return component.start(lambda: Node(name, client_library="rclcpp", **options))


@bag.command("info")
@click.argument("bag_path", metavar="BAG", type=click.Path(path_type=Path))
def info_(bag_path: Path) -> None:
    """Print a bag's files, size, duration, start and end, and its topics with counts.

    BAG is a bag folder (with or without metadata.yaml) or one .mcap file.

    \b
    Example:
      diffctl bag info run1
    """
    from diffctl.bag.info import format_info
    from diffctl.bag.reader import Bag

    b = Bag(bag_path)
    try:
        names = list(b.metadata.relative_file_paths) or [p.name for p in b.file_paths]
        console.print(format_info(b.metadata, b.size_bytes, names), end="", markup=False)
    finally:
        b.close()


@bag.command()
@click.argument("bag_path", metavar="BAG", type=click.Path(path_type=Path))
@click.option("-r", "--rate", type=float, default=1.0, help="Playback rate (1 = recorded pace).")
@click.option("-l", "--loop", is_flag=True, help="Play again from the start when the bag ends.")
@click.option("--clock", "clock_hz", type=float, is_flag=False, flag_value=40.0, default=0.0,
              help="Publish /clock at HZ (40 if no value) and drop the bag's own /clock.")
@click.option("--start-offset", type=float, default=0.0, help="Start this many seconds into the bag.")
@click.option("-p", "--start-paused", is_flag=True, help="Start paused (SPACE resumes).")
@click.option("--topics", multiple=True, help="Play only this topic (repeatable).")
@click.option("-m", "--remap", multiple=True, help="Publish topic OLD as NEW: OLD:=NEW (repeatable).")
@click.option("--read-ahead-queue-size", type=int, default=1000, help="Messages read ahead of playback.")
def play(bag_path: Path, rate: float, loop: bool, clock_hz: float, start_offset: float, start_paused: bool,
         topics: tuple[str, ...], remap: tuple[str, ...], read_ahead_queue_size: int) -> None:
    """Publish a bag's messages with their recorded timing.

    Keys (in a terminal): SPACE pauses and resumes, → publishes the next message while paused,
    ↑/↓ change the rate by 0.1.

    \b
    Example:
      diffctl bag play run1 --clock --rate 2
      diffctl bag play run1 --topics /tf --remap /tf:=/replayed_tf
    """
    from diffctl.bag.bus_side import make_publishers, parse_remaps, plan_topics
    from diffctl.bag.keys import TerminalKeys
    from diffctl.bag.player import RATE_STEP, Player, PlayOptions
    from diffctl.bag.reader import Bag
    from diffctl.interfaces import types

    options = PlayOptions(rate=rate, loop=loop, clock_hz=clock_hz, start_offset_s=start_offset,
                          start_paused=start_paused, read_ahead=read_ahead_queue_size)
    remaps = parse_remaps(remap)
    b = Bag(bag_path)
    try:
        notes: list[str] = []
        played = plan_topics(b, topics, remaps, {"/clock"} if clock_hz else set(), warn=notes.append)
        if not played:
            raise ConfigError(f"{bag_path}: nothing to play", hint="the bag has no messages on the chosen topics")
        stop = stop_on_signals()
        started = _start_node("rosbag2_player")
        log = started.node.get_logger()
        for note in notes:
            log.warning(note)
        node = started.node.bus_node  # the recorded bytes go out as they are, on raw publishers
        pubs = make_publishers(node, played)
        clock_pub = node.create_publisher("/clock", "rosgraph_msgs/msg/Clock") if clock_hz else None
        wanted = set(pubs)

        def publish_clock(ns: int) -> None:
            assert clock_pub is not None
            clock_pub.publish(types.new("rosgraph_msgs/msg/Clock", {"clock": {"sec": ns // 1_000_000_000,
                                                                             "nanosec": ns % 1_000_000_000}}))

        player = Player(lambda from_ns: b.messages(wanted, from_ns), b.metadata.starting_time_ns, options,
                        lambda m: pubs[m.topic](m.data), publish_clock if clock_pub else None)

        def on_key(key: str) -> None:  # rosbag2's player's words for each key
            if key == "space":
                log.info("Pausing play." if player.toggle_pause() else "Resuming play.")
            elif key == "right" and not player.step():
                log.warning("Called play next, but not in paused state.")
            elif key in ("up", "down"):
                log.info(f"Set rate to {player.change_rate(RATE_STEP if key == 'up' else -RATE_STEP):g}")

        threading.Thread(target=lambda: (stop.wait(), player.stop()), daemon=True).start()
        time.sleep(0.3)  # let subscribers' routes to the new publishers settle before the first message
        with TerminalKeys(on_key) as keys:
            if keys.active:
                log.info("Adding keyboard callbacks.")
                for key, what in (("SPACE", "Pause/Resume"), ("CURSOR_RIGHT", "Play Next Message"),
                                  ("CURSOR_UP", "Increase Rate 10%"), ("CURSOR_DOWN", "Decrease Rate 10%")):
                    log.info(f"Press {key} for {what}")
            n = player.run()
        time.sleep(0.2)  # the last samples leave before the session closes
        log.info(f"Played {n} messages")
        started.stop()
    finally:
        b.close()


@bag.command("reindex")
@click.argument("bag_dir", metavar="DIR", type=click.Path(path_type=Path))
def reindex_(bag_dir: Path) -> None:
    """Rebuild metadata.yaml from a bag's files, first repairing files a killed recorder left unfinished.

    \b
    Example:
      diffctl bag reindex rosbag2_2024_05_01-12_00_00
    """
    from diffctl.bag.reindex import reindex

    repaired, count = reindex(bag_dir)
    for name in repaired:
        info(f"repaired {name} (kept every complete chunk)")
    console.print(f"reindexed {bag_dir}: {count} messages", markup=False)
