"""teleop_twist_joy's rule, pure: a Joy message's axes and buttons → the velocity command to send, if any.

The turbo button (when one is set and held) drives with the turbo scales; else the enable button (or no
button at all, when it is not required) with the normal ones; else the first message sends one zero command
to stop the robot and the following send nothing. Each velocity component is its axis times its scale, 0 for
an axis of -1 or one the message has not got. inverted_reverse mirrors the yaw while driving backwards.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

LINEAR = ("x", "y", "z")
ANGULAR = ("yaw", "pitch", "roll")
Vec3 = tuple[float, float, float]


GROUPS: dict[str, tuple[str, ...]] = {
    "axis_linear": LINEAR, "axis_angular": ANGULAR, "scale_linear": LINEAR, "scale_linear_turbo": LINEAR,
    "scale_angular": ANGULAR, "scale_angular_turbo": ANGULAR,
}
# teleop_node's parameters in its declaration order (a group's fields in key order, as rclcpp's
# declare_parameters walks its std::map), with its defaults, which fix their types.
DECLARED: tuple[tuple[str, object], ...] = (
    ("publish_stamped_twist", False), ("frame", "teleop_twist_joy"), ("require_enable_button", True),
    ("enable_button", 5), ("enable_turbo_button", -1), ("inverted_reverse", False),
    ("axis_linear.x", 5), ("axis_linear.y", -1), ("axis_linear.z", -1),
    ("axis_angular.pitch", -1), ("axis_angular.roll", -1), ("axis_angular.yaw", 2),
    ("scale_linear.x", 0.5), ("scale_linear.y", 0.0), ("scale_linear.z", 0.0),
    ("scale_linear_turbo.x", 1.0), ("scale_linear_turbo.y", 0.0), ("scale_linear_turbo.z", 0.0),
    ("scale_angular.pitch", 0.0), ("scale_angular.roll", 0.0), ("scale_angular.yaw", 0.5),
    ("scale_angular_turbo.pitch", 0.0), ("scale_angular_turbo.roll", 0.0), ("scale_angular_turbo.yaw", 1.0),
)
# What a parameter change at run time updates (the publisher's type and the frame stay as started).
LIVE = ("require_enable_button", "enable_button", "enable_turbo_button", "inverted_reverse")


@dataclass
class Settings:
    """The node's current parameter values: flags and buttons, and per group its fields' axes or scales."""

    require_enable_button: bool
    enable_button: int
    enable_turbo_button: int
    inverted_reverse: bool
    groups: dict[str, dict[str, Any]]

    @classmethod
    def from_values(cls, values: Mapping[str, Any]) -> Settings:
        """From every declared name's value (DECLARED's defaults filling in the rest)."""
        v = {**dict(DECLARED), **values}
        return cls(bool(v["require_enable_button"]), int(v["enable_button"]), int(v["enable_turbo_button"]),
                   bool(v["inverted_reverse"]),
                   {g: {f: v[f"{g}.{f}"] for f in fields} for g, fields in GROUPS.items()})

    def update(self, name: str, value: Any) -> None:
        group, _, f = name.partition(".")
        if name in LIVE:
            setattr(self, name, value)
        elif group in GROUPS and f in GROUPS[group]:
            self.groups[group][f] = value


@dataclass(frozen=True)
class Command:
    linear: Vec3
    angular: Vec3  # (x, y, z) = (roll, pitch, yaw) rates


STOP = Command((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


def _held(buttons: list[int], index: int) -> bool:
    return 0 <= index < len(buttons) and bool(buttons[index])


def _term(axes: list[float], index: int, scale: float) -> float:
    return axes[index] * scale if 0 <= index < len(axes) else 0.0


def command(s: Settings, axes: list[float], turbo: bool) -> Command:
    g = s.groups
    lin_scale = g["scale_linear_turbo" if turbo else "scale_linear"]
    ang_scale = g["scale_angular_turbo" if turbo else "scale_angular"]
    lx, ly, lz = (_term(axes, g["axis_linear"][f], lin_scale[f]) for f in LINEAR)
    yaw, pitch, roll = (_term(axes, g["axis_angular"][f], ang_scale[f]) for f in ANGULAR)
    if s.inverted_reverse and lx < 0.0:
        yaw = -yaw
    return Command((lx, ly, lz), (roll, pitch, yaw))


class TeleopTwistJoy:
    def __init__(self, settings: Settings) -> None:
        self.settings = settings
        self.sent_disable_msg = False

    def on_joy(self, axes: list[float], buttons: list[int]) -> Command | None:
        s = self.settings
        if s.enable_turbo_button >= 0 and _held(buttons, s.enable_turbo_button):
            self.sent_disable_msg = False
            return command(s, axes, turbo=True)
        if not s.require_enable_button or _held(buttons, s.enable_button):
            self.sent_disable_msg = False
            return command(s, axes, turbo=False)
        if self.sent_disable_msg:
            return None
        self.sent_disable_msg = True
        return STOP
