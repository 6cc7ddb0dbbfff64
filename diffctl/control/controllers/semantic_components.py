"""ros2_control's semantic components (IMUSensor, RangeSensor, ForceTorqueSensor): the state interface names a
sensor broadcaster claims, and its values read into a message.

A sensor `name` gives the standard names `<name>/orientation.x` … (IMU), `<name>/range`, `<name>/force.x` …
`<name>/torque.z` (a 6-axis force-torque sensor); a force-torque sensor may instead name each axis's interface
itself, leaving out the axes it does not have (their values read as 0).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from diffctl.errors import RuntimeFailure

IMU_FIELDS = ("orientation.x", "orientation.y", "orientation.z", "orientation.w", "angular_velocity.x",
              "angular_velocity.y", "angular_velocity.z", "linear_acceleration.x", "linear_acceleration.y",
              "linear_acceleration.z")
WRENCH_FIELDS = ("force.x", "force.y", "force.z", "torque.x", "torque.y", "torque.z")


def imu_interfaces(sensor: str) -> list[str]:
    return [f"{sensor}/{f}" for f in IMU_FIELDS]


def range_interfaces(sensor: str) -> list[str]:
    return [f"{sensor}/range"]


def wrench_interfaces(sensor: str = "", per_axis: Sequence[str] = ("",) * 6) -> list[str]:
    """The six axes' interface names ("" for an axis the sensor does not have)."""
    if sensor:
        return [f"{sensor}/{f}" for f in WRENCH_FIELDS]
    return list(per_axis)


def bind(names: Sequence[str], handles: Sequence[Any]) -> list[Any]:
    """The handle of each name (None where the name is ""), or raise naming the first one missing."""
    by_name = {h.name: h for h in handles}
    out = []
    for name in names:
        if not name:
            out.append(None)
            continue
        if name not in by_name:
            raise RuntimeFailure(f"state interface {name!r} was not given to this controller "
                                 f"(it has {sorted(by_name) or 'none'})")
        out.append(by_name[name])
    return out
