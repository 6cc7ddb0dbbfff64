"""Commands the page sends that publish on the bus: teleop twists and the message publisher's jobs.

Everything arriving from the browser is checked here before it goes near a publisher: numbers must be
finite, speeds are clamped to the configured limits, topics must be valid names, bodies must convert to
their message type. A bad command raises MessageError, which the page shows; nothing is published.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import yaml

from diffctl.errors import MessageError
from diffctl.viz.settings import VizSettings, valid_topic

MAX_BODY_CHARS = 64_000
TWIST = "geometry_msgs/msg/Twist"
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"


@dataclass(frozen=True)
class TeleopCommand:
    topic: str
    stamped: bool
    linear_mps: float
    angular_radps: float

    @property
    def is_zero(self) -> bool:
        return self.linear_mps == 0.0 and self.angular_radps == 0.0

    def zero(self) -> TeleopCommand:
        return TeleopCommand(self.topic, self.stamped, 0.0, 0.0)

    @property
    def type_name(self) -> str:
        return TWIST_STAMPED if self.stamped else TWIST

    def fields(self, stamp: dict[str, int], frame_id: str) -> dict[str, Any]:
        twist = {"linear": {"x": self.linear_mps}, "angular": {"z": self.angular_radps}}
        if not self.stamped:
            return twist
        return {"header": {"stamp": stamp, "frame_id": frame_id}, "twist": twist}


def _number(obj: dict[str, Any], key: str) -> float:
    v = obj.get(key, 0.0)
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        raise MessageError(f"teleop {key} must be a finite number, got {v!r}")
    return float(v)


def _topic(value: Any, what: str) -> str:
    if not isinstance(value, str) or not valid_topic(value.strip()):
        raise MessageError(f"{what} must be a topic name such as /diffbot_base_controller/cmd_vel, got {value!r}")
    name = value.strip()
    return name if name.startswith("/") else "/" + name


def parse_teleop(obj: dict[str, Any], settings: VizSettings) -> TeleopCommand:
    """A teleop command from the page, clamped to the speed limits."""
    topic = _topic(obj.get("topic", settings.teleop_topic), "teleop topic")
    stamped = obj.get("stamped", settings.teleop_stamped)
    if not isinstance(stamped, bool):
        raise MessageError(f"teleop stamped must be true or false, got {stamped!r}")
    lin = max(-settings.max_linear_mps, min(settings.max_linear_mps, _number(obj, "linear")))
    ang = max(-settings.max_angular_radps, min(settings.max_angular_radps, _number(obj, "angular")))
    return TeleopCommand(topic, stamped, lin, ang)


@dataclass(frozen=True)
class PublishJob:
    """One row of the message publisher: `fields` go through types.new at each publish, so `now` and
    `auto` stamps are fresh every time."""

    id: str
    topic: str
    type_name: str
    fields: dict[str, Any]
    rate_hz: float  # 0 = publish once


def _reject_non_finite(value: Any, path: str) -> None:
    if isinstance(value, float) and not math.isfinite(value):
        raise MessageError(f"{path or 'body'} is {value!r}: NaN and infinity are not published")
    if isinstance(value, dict):
        for k, v in value.items():
            _reject_non_finite(v, f"{path}.{k}" if path else str(k))
    elif isinstance(value, list | tuple):
        for i, v in enumerate(value):
            _reject_non_finite(v, f"{path}[{i}]")


def parse_body(text: Any) -> dict[str, Any]:
    """A message body written in YAML or JSON, as `ros2 topic pub` takes it."""
    if not isinstance(text, str):
        raise MessageError(f"message body must be text, got {type(text).__name__}")
    if len(text) > MAX_BODY_CHARS:
        raise MessageError(f"message body is {len(text)} characters, at most {MAX_BODY_CHARS} are accepted")
    try:
        data = yaml.safe_load(text) if text.strip() else {}
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        raise MessageError(f"message body is not valid YAML{where}: {getattr(e, 'problem', None) or e}") from None
    if data is None:
        data = {}
    if not isinstance(data, dict):
        raise MessageError(f"message body must be a mapping of fields, e.g. {{linear: {{x: 0.5}}}}, got {data!r}")
    _reject_non_finite(data, "")
    return data


def fill_now(value: Any, stamp: dict[str, int]) -> Any:
    """`ros2 topic pub`'s keywords: a time written `now` takes the current time, a header written `auto`
    takes the current time and an empty frame_id."""
    if isinstance(value, dict):
        return {
            k: {"stamp": dict(stamp), "frame_id": ""} if k == "header" and v == "auto" else fill_now(v, stamp)
            for k, v in value.items()
        }
    if isinstance(value, list):
        return [fill_now(v, stamp) for v in value]
    return dict(stamp) if value == "now" else value


def parse_publish(obj: dict[str, Any], settings: VizSettings) -> PublishJob:
    """A message publisher job; the body is converted once here so a bad field is reported before anything
    is published."""
    from diffctl.interfaces import types

    job_id = str(obj.get("id", "")).strip()[:64] or "0"
    topic = _topic(obj.get("topic"), "topic")
    type_name = obj.get("type")
    if not isinstance(type_name, str) or not type_name.strip():
        raise MessageError("message type is missing, e.g. geometry_msgs/msg/TwistStamped")
    fields = parse_body(obj.get("body", ""))
    rate = obj.get("rate", 0)
    if isinstance(rate, str):
        try:
            rate = float(rate) if rate.strip() else 0.0
        except ValueError:
            raise MessageError(f"rate must be a number of hertz, got {rate!r}") from None
    if (
        isinstance(rate, bool)
        or not isinstance(rate, int | float)
        or not math.isfinite(rate)
        or not (0 <= rate <= settings.publisher_max_rate_hz)
    ):
        raise MessageError(f"rate must be between 0 (once) and {settings.publisher_max_rate_hz:g} Hz, got {rate!r}")
    cls = types.get_class(type_name.strip())
    full_name = getattr(cls, "__msgtype__", type_name.strip())
    types.new(full_name, fill_now(fields, {"sec": 0, "nanosec": 0}))  # raises MessageError naming the bad field
    return PublishJob(job_id, topic, full_name, fields, float(rate))
