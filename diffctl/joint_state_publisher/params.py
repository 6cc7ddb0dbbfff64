"""joint_state_publisher's parameters, validated into one frozen dataclass.

Names and defaults are the ROS node's: rate (10), source_list ([]), zeros.<joint>,
dependent_joints.<joint>.{parent,factor,offset}, use_mimic_tags (true), use_smallest_joint_limits
(true), publish_default_positions (true), publish_default_velocities/efforts (false), delta (0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from diffctl.errors import ParameterError


@dataclass(frozen=True)
class Dependent:
    """A joint that follows another: position = parent·factor + offset."""

    parent: str
    factor: float = 1.0
    offset: float = 0.0


@dataclass(frozen=True)
class JspParams:
    rate_hz: int = 10
    source_list: tuple[str, ...] = ()
    zeros: dict[str, float] = field(default_factory=dict)
    dependent_joints: dict[str, Dependent] = field(default_factory=dict)
    use_mimic_tags: bool = True
    use_smallest_joint_limits: bool = True
    publish_default_positions: bool = True
    publish_default_velocities: bool = False
    publish_default_efforts: bool = False
    delta_rad: float = 0.0
    use_sim_time: bool = False

    @staticmethod
    def from_dict(params: dict[str, Any]) -> JspParams:
        """Validated parameters (flattened `a.b` names or nested dicts); unknown names are ignored."""
        flat = _flatten(params)
        rate = flat.get("rate", 10)
        if isinstance(rate, bool) or not isinstance(rate, int) or not 1 <= rate <= 10_000:
            raise ParameterError(f"parameter 'rate' must be an integer in 1..10000 Hz, got {rate!r}", field="rate")
        sources = flat.get("source_list", [])
        if isinstance(sources, str) or not isinstance(sources, list | tuple) or not all(
            isinstance(s, str) and s for s in sources
        ):
            raise ParameterError(
                f"parameter 'source_list' must be a list of topic names, got {sources!r}", field="source_list"
            )
        zeros = {k[len("zeros.") :]: _number(k, v) for k, v in flat.items() if k.startswith("zeros.")}
        return JspParams(
            rate_hz=rate,
            source_list=tuple(sources),
            zeros=zeros,
            dependent_joints=_dependents(flat),
            use_mimic_tags=_bool(flat, "use_mimic_tags", True),
            use_smallest_joint_limits=_bool(flat, "use_smallest_joint_limits", True),
            publish_default_positions=_bool(flat, "publish_default_positions", True),
            publish_default_velocities=_bool(flat, "publish_default_velocities", False),
            publish_default_efforts=_bool(flat, "publish_default_efforts", False),
            delta_rad=_number("delta", flat.get("delta", 0.0)),
            use_sim_time=_bool(flat, "use_sim_time", False),
        )


def _flatten(d: dict[str, Any], prefix: str = "") -> dict[str, Any]:
    out: dict[str, Any] = {}
    for k, v in d.items():
        if isinstance(v, dict):
            out.update(_flatten(v, f"{prefix}{k}."))
        else:
            out[f"{prefix}{k}"] = v
    return out


def _number(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ParameterError(f"parameter {name!r} must be a finite number, got {value!r}", field=name)
    return float(value)


def _bool(flat: dict[str, Any], name: str, default: bool) -> bool:
    value = flat.get(name, default)
    if isinstance(value, str) and value.strip().lower() in ("true", "false"):
        return value.strip().lower() == "true"
    if not isinstance(value, bool):
        raise ParameterError(f"parameter {name!r} must be true or false, got {value!r}", field=name)
    return value


def _dependents(flat: dict[str, Any]) -> dict[str, Dependent]:
    fields: dict[str, dict[str, Any]] = {}
    for key, value in flat.items():
        if not key.startswith("dependent_joints."):
            continue
        parts = key.split(".")
        if len(parts) != 3 or parts[2] not in ("parent", "factor", "offset"):
            raise ParameterError(
                f"parameter {key!r} is not a dependent joint field",
                field=key,
                hint="write dependent_joints.<joint>.parent, .factor or .offset",
            )
        fields.setdefault(parts[1], {})[parts[2]] = value
    out = {}
    for joint, f in fields.items():
        parent = f.get("parent")
        if not isinstance(parent, str) or not parent:
            raise ParameterError(
                f"dependent joint {joint!r} has no parent", field=f"dependent_joints.{joint}.parent"
            )
        out[joint] = Dependent(
            parent,
            _number(f"dependent_joints.{joint}.factor", f.get("factor", 1.0)),
            _number(f"dependent_joints.{joint}.offset", f.get("offset", 0.0)),
        )
    return out
