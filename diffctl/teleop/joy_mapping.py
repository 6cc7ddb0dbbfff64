"""Pure game pad logic: raw input events → joy axes/buttons → velocity commands, as joy + teleop_twist_joy.

Axes follow ROS `joy`'s convention (stick left/up = +1, a released trigger = +1) with joy's deadzone
rescaling. The command logic is teleop_twist_joy's: the turbo button drives with turbo scales, the enable
button (unless not required) with normal scales, and releasing sends exactly one zero command.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from diffctl.teleop.joy_config import JoyParams
from diffctl.teleop.linux_input import AXES, BUTTONS, EV_ABS, EV_KEY

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class AxisRange:
    """An absolute axis' raw range (struct input_absinfo minimum/maximum)."""

    minimum: int
    maximum: int


@dataclass(frozen=True)
class Command:
    linear_m_s: Vec3
    angular_rad_s: Vec3  # (roll, pitch, yaw) rates about x, y, z

    @property
    def is_zero(self) -> bool:
        return not any(self.linear_m_s) and not any(self.angular_rad_s)


ZERO = Command((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


def normalize_axis(raw: int, rng: AxisRange, deadzone: float) -> float:
    """A raw axis value as joy publishes it: [-1, 1], sign flipped, deadzone cut and rescaled."""
    half = (rng.maximum - rng.minimum) / 2.0
    if half <= 0:
        return 0.0
    n = (raw - (rng.minimum + rng.maximum) / 2.0) / half
    n = max(-1.0, min(1.0, n))
    if abs(n) <= deadzone:
        return 0.0
    n = (abs(n) - deadzone) / (1.0 - deadzone) * (1.0 if n > 0 else -1.0)
    # Linux reports stick-down/right as positive; joy reports up/left as positive.
    return -n + 0.0


class JoyState:
    """Current axes (joy convention) and pressed buttons, updated from (type, code, value) events."""

    def __init__(self, ranges: Mapping[int, AxisRange], deadzone: float) -> None:
        self.ranges = dict(ranges)
        self.deadzone = deadzone
        self.axes: dict[int, float] = {}
        self.pressed: set[int] = set()

    def apply(self, ev_type: int, code: int, value: int) -> None:
        if ev_type == EV_KEY:
            # value 2 is autorepeat of a held key.
            if value:
                self.pressed.add(code)
            else:
                self.pressed.discard(code)
        elif ev_type == EV_ABS and code in self.ranges:
            self.axes[code] = normalize_axis(value, self.ranges[code], self.deadzone)

    def apply_all(self, events: Iterable[tuple[int, int, int]]) -> None:
        for ev in events:
            self.apply(*ev)

    def axis(self, name: str | None) -> float:
        return self.axes.get(AXES[name], 0.0) if name else 0.0

    def button(self, name: str | None) -> bool:
        return name is not None and BUTTONS[name] in self.pressed


class JoyTeleop:
    """teleop_twist_joy's joy callback: `update(state)` → the command to publish, or None."""

    def __init__(self, params: JoyParams) -> None:
        self.params = params
        self.sent_disable_msg = False
        self.mode = "idle"

    def _command(self, state: JoyState, turbo: bool) -> Command:
        p = self.params
        lin_scale = p.scale_linear_turbo if turbo else p.scale_linear
        ang_scale = p.scale_angular_turbo if turbo else p.scale_angular
        lx, ly, lz = (state.axis(p.axis_linear[f]) * lin_scale[f] for f in ("x", "y", "z"))
        yaw, pitch, roll = (state.axis(p.axis_angular[f]) * ang_scale[f] for f in ("yaw", "pitch", "roll"))
        if p.inverted_reverse and lx < 0:
            yaw = -yaw
        return Command((lx + 0.0, ly + 0.0, lz + 0.0), (roll + 0.0, pitch + 0.0, yaw + 0.0))

    def update(self, state: JoyState) -> Command | None:
        p = self.params
        if state.button(p.enable_turbo_button):
            self.mode = "turbo"
        elif not p.require_enable_button or state.button(p.enable_button):
            self.mode = "normal"
        else:
            self.mode = "idle"
            # Releasing enable stops the robot with one zero command, then stays silent.
            if self.sent_disable_msg:
                return None
            self.sent_disable_msg = True
            return ZERO
        self.sent_disable_msg = False
        return self._command(state, self.mode == "turbo")
