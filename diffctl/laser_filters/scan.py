"""A LaserScan as the filters see it: its geometry, and ranges/intensities as float32 arrays."""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np


@dataclass
class Scan:
    stamp_ns: int
    frame_id: str
    angle_min: float
    angle_max: float
    angle_increment: float
    time_increment: float
    scan_time: float
    range_min: float
    range_max: float
    ranges: np.ndarray
    intensities: np.ndarray

    def copy(self, **changes: Any) -> Scan:
        fresh = {"ranges": self.ranges.copy(), "intensities": self.intensities.copy()}
        return replace(self, **{**fresh, **changes})


def from_message(m: Any) -> Scan:
    stamp = m.header.stamp
    return Scan(int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec), str(m.header.frame_id), float(m.angle_min),
                float(m.angle_max), float(m.angle_increment), float(m.time_increment), float(m.scan_time),
                float(m.range_min), float(m.range_max), np.array(m.ranges, dtype=np.float32),
                np.array(m.intensities, dtype=np.float32))


def to_message(scan: Scan, cls: Any) -> Any:
    m = cls(angle_min=scan.angle_min, angle_max=scan.angle_max, angle_increment=scan.angle_increment,
            time_increment=scan.time_increment, scan_time=scan.scan_time, range_min=scan.range_min,
            range_max=scan.range_max, ranges=scan.ranges.tolist(), intensities=scan.intensities.tolist())
    m.header.frame_id = scan.frame_id
    m.header.stamp.sec, m.header.stamp.nanosec = divmod(scan.stamp_ns, 1_000_000_000)
    return m
