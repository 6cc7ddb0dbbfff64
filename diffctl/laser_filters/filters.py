"""laser_filters' scan filters, pure: each is configured from its parameter values and turns a Scan into the
filtered Scan (or None: the chain stops and nothing is published).

Parameter names, the order they are read in and their types are laser_filters' (2.0.7). The filters library
declares a filter parameter the filter does not get with its *type's* default (0.0, false, 0, ''), whatever
default the filter's code meant; so does this. Comparisons are made as the C++ makes them: float32 readings
against double thresholds.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, Protocol

import numpy as np

from diffctl.errors import ParameterError
from diffctl.laser_filters.scan import Scan

Log = Callable[[str], None]


class Transforms(Protocol):
    """What the box filter needs of tf2: a bounded wait for a transform, and lookups at given times."""

    def can_transform(self, target: str, source: str, time_ns: int, timeout_s: float) -> tuple[bool, str]: ...

    def lookup(self, target: str, source: str, time_ns: int) -> tuple[tuple[float, float, float],
                                                                       tuple[float, float, float, float]]: ...


def _f32(x: float) -> float:
    return float(np.float32(x))


class RangeFilter:
    """laser_filters/LaserScanRangeFilter: readings at or below lower_threshold, or at or above upper_threshold,
    replaced (by lower_/upper_replacement_value); use_message_range_limits takes the scan's own limits."""

    PARAMS = (("use_message_range_limits", False), ("lower_replacement_value", 0.0),
              ("upper_replacement_value", 0.0), ("lower_threshold", 0.0), ("upper_threshold", 0.0))

    def __init__(self, values: dict[str, Any], log: Any) -> None:
        self.use_message_limits = bool(values["use_message_range_limits"])
        self.lower_value = _f32(values["lower_replacement_value"])
        self.upper_value = _f32(values["upper_replacement_value"])
        self.lower, self.upper = float(values["lower_threshold"]), float(values["upper_threshold"])

    def update(self, scan: Scan) -> Scan | None:
        if self.use_message_limits:
            self.lower, self.upper = scan.range_min, scan.range_max
        out = scan.copy()
        r = scan.ranges.astype(np.float64)
        low = r <= self.lower
        out.ranges[low] = self.lower_value
        out.ranges[~low & (r >= self.upper)] = self.upper_value
        return out


class IntensityFilter:
    """laser_filters/LaserScanIntensityFilter: readings whose intensity is at or below lower_threshold or at or
    above upper_threshold become NaN; disp_histogram (non-zero) prints a 24-bucket histogram of each scan."""

    PARAMS = (("lower_threshold", 0.0), ("upper_threshold", 0.0), ("disp_histogram", 0))
    HIST_MAX, BUCKETS = 4 * 12000.0, 24

    def __init__(self, values: dict[str, Any], log: Any) -> None:
        self.lower, self.upper = float(values["lower_threshold"]), float(values["upper_threshold"])
        self.histogram = int(values["disp_histogram"]) != 0

    def update(self, scan: Scan) -> Scan | None:
        out = scan.copy()
        n = min(len(scan.ranges), len(scan.intensities))
        intensity = scan.intensities[:n].astype(np.float64)
        out.ranges[:n][(intensity <= self.lower) | (intensity >= self.upper)] = np.nan
        if self.histogram:
            counted = intensity[np.isfinite(intensity)]
            buckets = np.clip(np.trunc(counted / self.HIST_MAX * self.BUCKETS), 0, self.BUCKETS - 1).astype(int)
            counts = np.bincount(buckets, minlength=self.BUCKETS)
            width = int(self.HIST_MAX) // self.BUCKETS
            lines = ["********** SCAN **********"]
            lines += [f"{width * i} - {width * (i + 1)}: {counts[i]}" for i in range(self.BUCKETS)]
            print("\n".join(lines), flush=True)
        return out


class AngularBoundsFilter:
    """laser_filters/LaserScanAngularBoundsFilter: the scan cut to the readings from lower_angle to upper_angle,
    its angle_min/angle_max and stamp moved to what is kept."""

    PARAMS = (("lower_angle", 0.0), ("upper_angle", 0.0))

    def __init__(self, values: dict[str, Any], log: Any) -> None:
        self.lower, self.upper = float(values["lower_angle"]), float(values["upper_angle"])

    def update(self, scan: Scan) -> Scan | None:
        start = current = scan.angle_min
        stamp = scan.stamp_ns
        step_ns = int(scan.time_increment * 1e9)
        kept: list[int] = []
        for i in range(len(scan.ranges)):
            if start < self.lower:
                start += scan.angle_increment
                current += scan.angle_increment
                stamp += step_ns
                continue
            kept.append(i)
            if current + scan.angle_increment > self.upper:
                break
            current += scan.angle_increment
        intensities = scan.intensities
        if len(intensities) >= len(kept):
            intensities = np.array([intensities[i] if i < len(intensities) else 0.0 for i in kept], np.float32)
        return scan.copy(stamp_ns=stamp, angle_min=start, angle_max=current, ranges=scan.ranges[kept],
                         intensities=intensities)


class AngularBoundsFilterInPlace:
    """laser_filters/LaserScanAngularBoundsFilterInPlace: readings strictly between lower_angle and upper_angle
    set beyond range (range_max + 1), their intensities to 0."""

    PARAMS = (("lower_angle", 0.0), ("upper_angle", 0.0))

    def __init__(self, values: dict[str, Any], log: Any) -> None:
        self.lower, self.upper = float(values["lower_angle"]), float(values["upper_angle"])

    def update(self, scan: Scan) -> Scan | None:
        out = scan.copy()
        angle = scan.angle_min
        for i in range(len(scan.ranges)):
            if self.lower < angle < self.upper:
                out.ranges[i] = scan.range_max + 1.0
                if i < len(out.intensities):
                    out.intensities[i] = 0.0
            angle += scan.angle_increment
        return out


class SpeckleFilter:
    """laser_filters/LaserScanSpeckleFilter: a reading stays if some window of filter_window consecutive readings
    holding it is consistent (filter_type 0: neighbours within max_range_difference of its range; 1: at least
    filter_window neighbours within max_range_difference in space), or if it is beyond max_range; else NaN."""

    PARAMS = (("filter_type", 0), ("max_range", 0.0), ("max_range_difference", 0.0), ("filter_window", 0))

    def __init__(self, values: dict[str, Any], log: Any) -> None:
        self.kind = int(values["filter_type"])
        if self.kind not in (0, 1):
            raise ParameterError(f"{self.kind} invalid; valid: 0 (Distance) or 1 (RadiusOutlier)",
                                 field="filter_type")
        self.max_range = float(values["max_range"])
        self.max_difference = float(values["max_range_difference"])
        self.window = int(values["filter_window"])

    def _distance_window(self, r: np.ndarray, idx: int) -> bool:
        if math.isnan(r[idx]):
            return False
        for k in range(idx + 1, min(idx + self.window, len(r))):
            if math.isnan(r[k]) or float(abs(r[k] - r[idx])) > self.max_difference:
                return False
        return True

    def _radius_window(self, r: np.ndarray, idx: int, increment: np.float32) -> bool:
        neighbours = 0
        r1 = r[idx]
        for y in range(-self.window, self.window + 1):
            if neighbours >= self.window:
                break
            j = idx + y
            if j < 0 or j >= len(r) or j == idx or math.isnan(r[j]):
                continue
            r2 = r[j]
            cross = np.float32(2.0) * r1 * r2 * np.float32(math.cos(np.float32(y) * increment))
            d = _f32(math.sqrt(float(r1) ** 2 + float(r2) ** 2 - float(cross)))
            if d <= self.max_difference:
                neighbours += 1
        return neighbours >= self.window

    def update(self, scan: Scan) -> Scan | None:
        out = scan.copy()
        r = scan.ranges
        n = len(r)
        valid = np.zeros(n, dtype=bool)
        increment = np.float32(scan.angle_increment)
        for idx in range(max(0, n - self.window + 1)):
            ok = self._distance_window(r, idx) if self.kind == 0 else self._radius_window(r, idx, increment)
            for k in range(idx, min(idx + max(self.window, 1), n)):
                valid[k] = valid[k] or ok or float(r[k]) > self.max_range
        out.ranges[~valid] = np.nan
        return out


class BoxFilter:
    """laser_filters/LaserScanBoxFilter: readings whose point lies inside the box (min_/max_ x, y, z in
    box_frame, strictly) become NaN; with invert, those outside. Points are placed as laser_geometry's
    transformLaserScanToPointCloud places them: valid ranges only, the transform interpolated over the scan."""

    PARAMS = (("box_frame", ""), ("max_x", 0.0), ("max_y", 0.0), ("max_z", 0.0), ("min_x", 0.0), ("min_y", 0.0),
              ("min_z", 0.0), ("invert", False))

    def __init__(self, values: dict[str, Any], log: Any, transforms: Transforms | None = None) -> None:
        self.frame = str(values["box_frame"])
        self.max = np.array([values["max_x"], values["max_y"], values["max_z"]], dtype=np.float64)
        self.min = np.array([values["min_x"], values["min_y"], values["min_z"]], dtype=np.float64)
        self.remove_inside = not bool(values["invert"])
        self.transforms = transforms
        self.log = log

    def points(self, scan: Scan) -> tuple[np.ndarray, np.ndarray] | None:
        """(indices, float32 xyz in box_frame) of the valid readings; None when a transform is missing."""
        from diffctl.tf2 import transform_math as tm

        assert self.transforms is not None
        n = len(scan.ranges)
        r = scan.ranges.astype(np.float64)
        index = np.nonzero((r < scan.range_max) & (r >= scan.range_min))[0]
        angles = scan.angle_min + index * scan.angle_increment
        local = np.stack([r[index] * np.cos(angles), r[index] * np.sin(angles), np.zeros(len(index))], axis=1)
        local = local.astype(np.float32).astype(np.float64)
        end_ns = scan.stamp_ns + (int((n - 1) * scan.time_increment * 1e9) if n else 0)
        t0, q0 = self.transforms.lookup(self.frame, scan.frame_id, scan.stamp_ns)
        t1, q1 = self.transforms.lookup(self.frame, scan.frame_id, end_ns)
        out = np.empty_like(local)
        for k, (i, p) in enumerate(zip(index, local, strict=True)):
            ratio = i / (n - 1.0) if n > 1 else 0.0
            t, q = tm.lerp(t0, t1, ratio), tm.slerp(q0, q1, ratio)
            moved = tm.rotate(q, tuple(p))
            out[k] = (moved[0] + t[0], moved[1] + t[1], moved[2] + t[2])
        return index, out.astype(np.float32)

    def update(self, scan: Scan) -> Scan | None:
        if self.transforms is None:
            return None
        when = scan.stamp_ns + int(len(scan.ranges) * scan.time_increment * 1e9)
        ok, error = self.transforms.can_transform(self.frame, scan.frame_id, when, 1.0)
        if not ok:
            self.log.warning(f"Could not get transform, irgnoring laser scan! {error}")
            return None
        out = scan.copy()
        try:
            found = self.points(scan)
        except LookupError as e:
            self.log.warning(f"Dropping Scan: Tansform unavailable {e}", throttle_duration_sec=1.0)
            return out
        if found is None:
            return out
        index, xyz = found
        p = xyz.astype(np.float64)
        inside = np.all((p < self.max) & (p > self.min), axis=1)
        out.ranges[index[inside == self.remove_inside]] = np.nan
        return out


FILTERS: dict[str, type] = {
    "laser_filters/LaserScanRangeFilter": RangeFilter,
    "laser_filters/LaserScanIntensityFilter": IntensityFilter,
    "laser_filters/LaserScanAngularBoundsFilter": AngularBoundsFilter,
    "laser_filters/LaserScanAngularBoundsFilterInPlace": AngularBoundsFilterInPlace,
    "laser_filters/LaserScanSpeckleFilter": SpeckleFilter,
    "laser_filters/LaserScanBoxFilter": BoxFilter,
}
# laser_filters' other plugins: named so a chain naming one is told it is not provided
NOT_PROVIDED = ("laser_filters/LaserMedianFilter", "laser_filters/LaserArrayFilter",
                "laser_filters/LaserScanFootprintFilter", "laser_filters/ScanShadowsFilter",
                "laser_filters/InterpolationFilter", "laser_filters/LaserScanMaskFilter")
