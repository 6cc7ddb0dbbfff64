"""The visualizer's parameters, declared once and validated in one place.

They come from `--ros-args -p name:=value` (as a launch file passes them) and from the command line's
options, which win. Stream rates are caps: the page never gets more than this, whatever the topics publish.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, fields
from typing import Any

from diffctl.errors import ParameterError

TOPIC_RE = re.compile(r"^/?[A-Za-z_~][A-Za-z0-9_/~{}]*$")


def valid_topic(name: str) -> bool:
    return bool(TOPIC_RE.match(name)) and "//" not in name and not name.endswith("/")


@dataclass(frozen=True)
class VizSettings:
    host: str = "127.0.0.1"
    port: int = 8080
    use_sim_time: bool = False
    fixed_frame: str | None = None  # overrides the .rviz file's Fixed Frame
    teleop_topic: str = "/diffbot_base_controller/cmd_vel"
    teleop_stamped: bool = True
    teleop_frame_id: str = ""
    max_linear_mps: float = 1.0  # hard limits: the page's sliders stop here and the server clamps to them
    max_angular_radps: float = 2.0
    frame_rate_hz: float = 30.0
    scan_rate_hz: float = 10.0
    image_rate_hz: float = 5.0
    publisher_max_rate_hz: float = 100.0
    teleop_timeout_s: float = 0.5  # a held command not refreshed for this long is followed by a zero
    ground_truth_model: str = "robot"
    path_max_points: int = 2000

    def __post_init__(self) -> None:
        def bad(name: str, why: str) -> ParameterError:
            return ParameterError(f"{why}, got {getattr(self, name)!r}", field=name)

        if not self.host or any(c.isspace() for c in self.host):
            raise bad("host", "must be a host name or address")
        if not (0 <= self.port <= 65535):
            raise bad("port", "must be a TCP port in 0..65535 (0 = pick a free one)")
        if not valid_topic(self.teleop_topic):
            raise bad("teleop_topic", "must be a ROS topic name such as /diffbot_base_controller/cmd_vel")
        limits = {
            "max_linear_mps": (0.0, 20.0),
            "max_angular_radps": (0.0, 50.0),
            "frame_rate_hz": (1.0, 60.0),
            "scan_rate_hz": (0.5, 60.0),
            "image_rate_hz": (0.2, 30.0),
            "publisher_max_rate_hz": (0.1, 1000.0),
            "teleop_timeout_s": (0.05, 10.0),
        }
        for name, (low, high) in limits.items():
            v = getattr(self, name)
            if not (math.isfinite(v) and low < v <= high):
                raise bad(name, f"must be a number in ({low:g}, {high:g}]")
        if not (10 <= self.path_max_points <= 1_000_000):
            raise bad("path_max_points", "must be an integer in [10, 1000000]")

    @classmethod
    def from_params(cls, params: dict[str, Any], **overrides: Any) -> VizSettings:
        """Settings from ROS parameters (unknown ones ignored: launch files pass rviz2's own) and options."""
        known = {f.name: f for f in fields(cls)}
        values: dict[str, Any] = {}
        for name, value in {**params, **{k: v for k, v in overrides.items() if v is not None}}.items():
            if name not in known:
                continue
            default = known[name].default
            values[name] = _coerce(name, value, default)
        return cls(**values)


def _coerce(name: str, value: Any, default: Any) -> Any:
    try:
        if isinstance(default, bool):
            if isinstance(value, str) and value.lower() in ("true", "false"):
                return value.lower() == "true"
            if not isinstance(value, bool):
                raise TypeError
            return value
        if isinstance(default, int):
            if isinstance(value, bool) or float(value) != int(float(value)):
                raise TypeError
            return int(float(value))
        if isinstance(default, float):
            if isinstance(value, bool):
                raise TypeError
            return float(value)
        return None if value is None else str(value)
    except (TypeError, ValueError):
        kind = type(default).__name__ if default is not None else "string"
        raise ParameterError(f"must be a {kind}, got {value!r}", field=name) from None
