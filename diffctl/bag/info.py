"""`bag info` text, laid out as rosbag2_py's format_bag_metadata prints it (labels padded to 19 columns)."""

from __future__ import annotations

import time

from diffctl.bag.metadata import BagMetadata

_PAD = 19


def file_size(size_bytes: int) -> str:
    """rosbag2's 1024-based size with one decimal: `12.3 KiB`."""
    units = ("B", "KiB", "MiB", "GiB", "TiB")
    size = float(size_bytes)
    i = 0
    while size >= 1024 and i < len(units) - 1:
        size /= 1024
        i += 1
    return f"{size_bytes} B" if i == 0 else f"{size:.1f} {units[i]}"


def stamp(ns: int) -> str:
    """`%b %e %Y %H:%M:%S.<ns> (<s>.<ns>)` in local time, as ros2 bag info shows a time point."""
    sec, nsec = divmod(ns, 1_000_000_000)
    return f"{time.strftime('%b %e %Y %H:%M:%S', time.localtime(sec))}.{nsec:09d} ({sec}.{nsec:09d})"


def duration(ns: int) -> str:
    sec, nsec = divmod(ns, 1_000_000_000)
    return f"{sec}.{nsec:09d}s"


def _label(name: str) -> str:
    return f"{name}:".ljust(_PAD)


def format_info(meta: BagMetadata, size_bytes: int, file_names: list[str]) -> str:
    lines = [""]
    files = file_names or ["(none)"]
    lines.append(_label("Files") + files[0])
    lines += [" " * _PAD + f for f in files[1:]]
    lines.append(_label("Bag size") + file_size(size_bytes))
    lines.append(_label("Storage id") + meta.storage_identifier)
    lines.append(_label("ROS Distro") + (meta.ros_distro or "unknown"))
    lines.append(_label("Duration") + duration(meta.duration_ns))
    lines.append(_label("Start") + stamp(meta.starting_time_ns))
    lines.append(_label("End") + stamp(meta.end_ns))
    lines.append(_label("Messages") + str(meta.message_count))
    topics = [f"Topic: {t.name} | Type: {t.type} | Count: {t.message_count} | "
              f"Serialization Format: {t.serialization_format}" for t in meta.topics]
    lines.append(_label("Topic information") + (topics[0] if topics else ""))
    lines += [" " * _PAD + t for t in topics[1:]]
    lines.append(_label("Service") + "0")
    lines.append("Service information: ")
    return "\n".join(lines) + "\n"
