"""teleop_twist_joy's parameters and `joy_config` presets, validated once into a frozen JoyParams.

Parameter names, defaults and precedence are teleop_twist_joy's (plus joy's `deadzone` and
`autorepeat_rate`, since diffctl reads the device itself). Buttons and axes are given by name
(`LB`, `LEFTY`, see linux_input.py) or by SDL index as on ROS 2 Jazzy; -1 means "none".

The presets keep the intent of the upstream files' comments by naming buttons: upstream's xbox.config.yaml
says "enable_button: 2  # Left trigger button", but index 2 is X under SDL, so the preset says LB.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

from diffctl.errors import ParameterError, suggest
from diffctl.teleop.linux_input import AXES, BUTTONS, SDL_AXIS_ORDER, SDL_BUTTON_ORDER

LINEAR_FIELDS = ("x", "y", "z")
ANGULAR_FIELDS = ("yaw", "pitch", "roll")

PRESETS: dict[str, dict[str, Any]] = {
    "xbox": {
        "axis_linear.x": "LEFTY",
        "scale_linear.x": 0.7,
        "scale_linear_turbo.x": 1.5,
        "axis_angular.yaw": "LEFTX",
        "scale_angular.yaw": 0.4,
        "enable_button": "LB",
        "enable_turbo_button": "RB",
    },
    "ps3": {
        "axis_linear.x": "LEFTY",
        "scale_linear.x": 0.7,
        "scale_linear_turbo.x": 1.5,
        "axis_angular.yaw": "LEFTX",
        "scale_angular.yaw": 0.4,
        "enable_button": "L2",
        "enable_turbo_button": "L1",
    },
    "atk3": {
        "axis_linear.x": "LEFTY",
        "scale_linear.x": 0.7,
        "scale_linear_turbo.x": 1.5,
        "axis_angular.yaw": "LEFTX",
        "scale_angular.yaw": 0.4,
        "enable_button": "TRIGGER",
        "enable_turbo_button": "THUMB",
    },
}

# teleop_twist_joy's code defaults (what applies when neither a preset nor a parameter says otherwise).
DEFAULTS: dict[str, Any] = {
    "axis_linear.x": 5,
    "axis_linear.y": -1,
    "axis_linear.z": -1,
    "axis_angular.yaw": 2,
    "axis_angular.pitch": -1,
    "axis_angular.roll": -1,
    "scale_linear.x": 0.5,
    "scale_linear.y": 0.0,
    "scale_linear.z": 0.0,
    "scale_linear_turbo.x": 1.0,
    "scale_linear_turbo.y": 0.0,
    "scale_linear_turbo.z": 0.0,
    "scale_angular.yaw": 0.5,
    "scale_angular.pitch": 0.0,
    "scale_angular.roll": 0.0,
    "scale_angular_turbo.yaw": 1.0,
    "scale_angular_turbo.pitch": 0.0,
    "scale_angular_turbo.roll": 0.0,
    "enable_button": 5,
    "enable_turbo_button": -1,
    "require_enable_button": True,
    "inverted_reverse": False,
    "publish_stamped_twist": False,
    "frame": "teleop_twist_joy",
    "deadzone": 0.3,
    "autorepeat_rate": 20.0,
}

_GROUPS = {
    "axis_linear": LINEAR_FIELDS,
    "scale_linear": LINEAR_FIELDS,
    "scale_linear_turbo": LINEAR_FIELDS,
    "axis_angular": ANGULAR_FIELDS,
    "scale_angular": ANGULAR_FIELDS,
    "scale_angular_turbo": ANGULAR_FIELDS,
}
# Launch and node plumbing parameters this node accepts and does not use itself.
_IGNORED = (
    "use_sim_time",
    "joy_config",
    "config_filepath",
    "device_id",
    "device_name",
    "dev",
    "joy_dev",
    "sticky_buttons",
    "coalesce_interval_ms",
    "joy_vel",
)


def _bool(name: str, value: Any) -> bool:
    if isinstance(value, bool):
        return value
    if isinstance(value, str) and value.strip().lower() in ("true", "false"):
        return value.strip().lower() == "true"
    raise ParameterError(f"{value!r} invalid; valid: true, false", field=name)


def _number(name: str, value: Any, lo: float = -math.inf, hi: float = math.inf) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ParameterError(f"{value!r} invalid; valid: a finite number", field=name)
    if not lo <= value <= hi:
        raise ParameterError(f"{value!r} out of range; valid: {lo} to {hi}", field=name)
    return float(value)


def _control(name: str, value: Any, names: Mapping[str, int], sdl_order: tuple[str, ...], what: str) -> str | None:
    """A button or axis given by name or SDL index; None for -1 (unmapped)."""
    if isinstance(value, bool):
        raise ParameterError(f"{value!r} invalid; valid: a {what} name or index", field=name)
    if isinstance(value, int):
        if value == -1:
            return None
        if 0 <= value < len(sdl_order):
            return sdl_order[value]
        raise ParameterError(
            f"{what} index {value} invalid; valid: -1 (none) or 0..{len(sdl_order) - 1} "
            f"({', '.join(f'{i} {n}' for i, n in enumerate(sdl_order))})",
            field=name,
        )
    if isinstance(value, str) and value.strip().upper() in names:
        return value.strip().upper()
    raise ParameterError(
        f"{what} {value!r} unknown{suggest(str(value).upper(), names)}; valid: {', '.join(names)}", field=name
    )


@dataclass(frozen=True)
class JoyParams:
    """Validated teleop_twist_joy parameters; axes and buttons by name (None = unmapped)."""

    axis_linear: Mapping[str, str | None]
    axis_angular: Mapping[str, str | None]
    scale_linear: Mapping[str, float]
    scale_linear_turbo: Mapping[str, float]
    scale_angular: Mapping[str, float]
    scale_angular_turbo: Mapping[str, float]
    enable_button: str | None
    enable_turbo_button: str | None
    require_enable_button: bool
    inverted_reverse: bool
    publish_stamped_twist: bool
    frame: str
    deadzone: float
    autorepeat_rate_hz: float

    @classmethod
    def from_params(cls, params: Mapping[str, Any], joy_config: str | None = None) -> JoyParams:
        """Code defaults, then the `joy_config` preset, then `params` (flattened names, e.g. axis_linear.x)."""
        merged: dict[str, Any] = dict(DEFAULTS)
        preset = joy_config if joy_config is not None else params.get("joy_config")
        if preset is not None:
            if preset not in PRESETS:
                raise ParameterError(
                    f"{preset!r} unknown{suggest(str(preset), PRESETS)}; valid: {', '.join(PRESETS)}",
                    field="joy_config",
                )
            merged.update(PRESETS[preset])
        for k, v in params.items():
            group, _, sub = k.partition(".")
            if group in _GROUPS:
                if sub not in _GROUPS[group]:
                    raise ParameterError(f"unknown field {sub!r}; valid: {', '.join(_GROUPS[group])}", field=k)
            elif k not in DEFAULTS and k not in _IGNORED:
                continue  # other nodes' parameters (a shared params file) are not ours to judge
            merged[k] = v

        def axes(group: str) -> Mapping[str, str | None]:
            return MappingProxyType(
                {
                    f: _control(f"{group}.{f}", merged[f"{group}.{f}"], AXES, SDL_AXIS_ORDER, "axis")
                    for f in _GROUPS[group]
                }
            )

        def scales(group: str) -> Mapping[str, float]:
            return MappingProxyType({f: _number(f"{group}.{f}", merged[f"{group}.{f}"]) for f in _GROUPS[group]})

        frame = merged["frame"]
        if not isinstance(frame, str):
            raise ParameterError(f"{frame!r} invalid; valid: a frame id string", field="frame")
        return cls(
            axis_linear=axes("axis_linear"),
            axis_angular=axes("axis_angular"),
            scale_linear=scales("scale_linear"),
            scale_linear_turbo=scales("scale_linear_turbo"),
            scale_angular=scales("scale_angular"),
            scale_angular_turbo=scales("scale_angular_turbo"),
            enable_button=_control("enable_button", merged["enable_button"], BUTTONS, SDL_BUTTON_ORDER, "button"),
            enable_turbo_button=_control(
                "enable_turbo_button", merged["enable_turbo_button"], BUTTONS, SDL_BUTTON_ORDER, "button"
            ),
            require_enable_button=_bool("require_enable_button", merged["require_enable_button"]),
            inverted_reverse=_bool("inverted_reverse", merged["inverted_reverse"]),
            publish_stamped_twist=_bool("publish_stamped_twist", merged["publish_stamped_twist"]),
            frame=frame,
            deadzone=_number("deadzone", merged["deadzone"], 0.0, 0.99),
            autorepeat_rate_hz=_number("autorepeat_rate", merged["autorepeat_rate"], 0.0, 1000.0),
        )

    def __rich__(self) -> Any:
        from diffctl.console import table

        rows = [(f"axis_linear.{f}", v or "-") for f, v in self.axis_linear.items()]
        rows += [(f"axis_angular.{f}", v or "-") for f, v in self.axis_angular.items()]
        for group in ("scale_linear", "scale_linear_turbo", "scale_angular", "scale_angular_turbo"):
            rows += [(f"{group}.{f}", v) for f, v in getattr(self, group).items() if v]
        rows += [
            ("enable_button", self.enable_button or "-"),
            ("enable_turbo_button", self.enable_turbo_button or "-"),
            ("require_enable_button", self.require_enable_button),
            ("deadzone", self.deadzone),
            ("publish_stamped_twist", self.publish_stamped_twist),
            ("frame", self.frame),
        ]
        return table("teleop_twist_joy", ["parameter", "value"], rows)
