"""joy_node's message state, pure: joystick events in, the Joy axes/buttons and when to publish out.

The device is presented as SDL's joystick API presents it (what the real joy_node reads): the plain axes in
input-code order, then each hat as two axes (left/up positive), buttons in the kernel's order. Axis values
are SDL's signed 16-bit ones, turned into [-1, 1] with the deadzone cut out smoothly and the sign flipped
(forward and left positive), rounded to float32 as the message carries them.

Publishing follows joy_node's event loop, one event (or one timeout) per step: a button or hat change
publishes at once; an axis change marks the message "publish soon", and the next step that publishes nothing
else sends it; with no event, autorepeat_rate resends the message once its interval (whole milliseconds) has
passed since the last repeat.
"""

from __future__ import annotations

import struct
from collections.abc import Sequence
from dataclasses import dataclass

ABS_HAT0X = 0x10
HAT_COUNT = 4
# SDL's hat bits
HAT_UP, HAT_RIGHT, HAT_DOWN, HAT_LEFT = 1, 2, 4, 8
AXIS_MAX = 32767


def f32(value: float) -> float:
    return struct.unpack("=f", struct.pack("=f", value))[0]


@dataclass(frozen=True)
class Slot:
    """Where a joystick axis lands in the message: a plain axis, or one direction of a hat."""

    index: int
    hat: int | None = None  # the hat's rank among the device's hats
    vertical: bool = False


@dataclass(frozen=True)
class Layout:
    """The message's axis count and the slot of each joystick axis number."""

    axes: int
    slots: tuple[Slot, ...]

    def slot(self, number: int) -> Slot | None:
        return self.slots[number] if number < len(self.slots) else None


def sdl_layout(axis_codes: Sequence[int]) -> Layout:
    """Plain axes first, in code order; then two message axes per hat present (HATnX or HATnY), as SDL counts."""
    hat_codes = range(ABS_HAT0X, ABS_HAT0X + 2 * HAT_COUNT)
    plain = sorted(c for c in axis_codes if c not in hat_codes)
    hats = [k for k in range(HAT_COUNT) if {ABS_HAT0X + 2 * k, ABS_HAT0X + 2 * k + 1} & set(axis_codes)]
    slots = []
    for code in axis_codes:
        if code in hat_codes:
            k, vertical = divmod(code - ABS_HAT0X, 2)
            rank = hats.index(k)
            slots.append(Slot(len(plain) + 2 * rank + vertical, rank, bool(vertical)))
        else:
            slots.append(Slot(plain.index(code)))
    return Layout(len(plain) + 2 * len(hats), tuple(slots))


@dataclass(frozen=True)
class JoyParams:
    deadzone: float = 0.05
    autorepeat_rate_hz: float = 20.0
    sticky_buttons: bool = False
    coalesce_interval_ms: int = 1

    @property
    def autorepeat_interval_ms(self) -> int:
        # With autorepeat off the loop still wakes every 200 ms (to notice shutdown).
        return int(1000.0 / self.autorepeat_rate_hz) if self.autorepeat_rate_hz > 0.0 else 200


def axis_value(raw: int, deadzone: float) -> float:
    """An SDL axis value (-32768..32767) as joy_node publishes it."""
    if deadzone >= 1.0:
        return 0.0  # all of the range is dead (joy_node's own arithmetic makes that 0 × ∞, NaN)
    raw = max(raw, -AXIS_MAX)
    cut = AXIS_MAX * deadzone
    scale = f32(-1.0 / (1.0 - deadzone) / AXIS_MAX)
    if raw > cut:
        shifted = raw - cut
    elif raw < -cut:
        shifted = raw + cut
    else:
        shifted = 0.0
    return f32(shifted * scale) + 0.0


class JoyState:
    """The message being built and joy_node's publish decisions. Times are node-clock nanoseconds."""

    def __init__(self, params: JoyParams, now_ns: int) -> None:
        self.params = params
        self.axes: list[float] = []
        self.buttons: list[int] = []
        self.growable = False
        self.publish_soon = False
        self.publish_soon_ns = now_ns
        self.last_repeat_ns = now_ns
        self._hat_bits: dict[int, int] = {}
        self.warnings: list[str] = []

    def wait_ms(self) -> int:
        wait = self.params.autorepeat_interval_ms
        return min(wait, self.params.coalesce_interval_ms) if self.publish_soon else wait

    def attach(self, axes: int | None, buttons: int | None) -> None:
        """A device opened: sized from its counts, or (counts unknown) grown by the events that come."""
        self.growable = axes is None or buttons is None
        self.axes = [0.0] * (axes or 0)
        self.buttons = [0] * (buttons or 0)
        self._hat_bits.clear()

    def detach(self) -> None:
        self.axes, self.buttons = [], []
        self._hat_bits.clear()

    def _fits(self, values: list, index: int, what: str, fill: float | int) -> bool:
        if index < len(values):
            return True
        if self.growable:
            values.extend([fill] * (index + 1 - len(values)))
            return True
        self.warnings.append(f"Saw {what} too large for this device, ignoring")
        return False

    def initial_axis(self, index: int, raw: int) -> None:
        """An axis' value when the device opened: taken without an event, as SDL's initial state."""
        if self._fits(self.axes, index, "axes", 0.0):
            self.axes[index] = axis_value(raw, self.params.deadzone)

    def initial_button(self, index: int) -> None:
        """A button reported released when the device opened: nothing changes (its slot exists)."""
        self._fits(self.buttons, index, "button", 0)

    def axis(self, index: int, raw: int, now_ns: int) -> bool:
        if not self._fits(self.axes, index, "axes", 0.0):
            return False
        before = self.axes[index]
        self.axes[index] = axis_value(raw, self.params.deadzone)
        if self.axes[index] == before:
            return False
        if self.params.coalesce_interval_ms > 0 and not self.publish_soon:
            self.publish_soon, self.publish_soon_ns = True, now_ns
            return False
        if now_ns - self.publish_soon_ns >= self.params.coalesce_interval_ms * 1_000_000:
            self.publish_soon = False
            return True
        return False

    def button(self, index: int, pressed: bool) -> bool:
        if not self._fits(self.buttons, index, "button", 0):
            return False
        if self.params.sticky_buttons:
            if pressed:
                self.buttons[index] = 1 - self.buttons[index]
            return pressed
        self.buttons[index] = int(pressed)
        return True

    def hat(self, slot: Slot, raw: int) -> bool:
        """One direction of a hat moved (raw < 0: left/up). Applied as joy_node applies SDL's hat value: set
        the directions present; only a fully centred hat clears both axes."""
        assert slot.hat is not None
        first = slot.index - 1 if slot.vertical else slot.index
        if not self._fits(self.axes, first + 1, "hat", 0.0):
            return False
        bits = self._hat_bits.get(slot.hat, 0)
        if slot.vertical:
            bits = (bits & ~(HAT_UP | HAT_DOWN)) | (HAT_UP if raw < 0 else HAT_DOWN if raw > 0 else 0)
        else:
            bits = (bits & ~(HAT_LEFT | HAT_RIGHT)) | (HAT_LEFT if raw < 0 else HAT_RIGHT if raw > 0 else 0)
        self._hat_bits[slot.hat] = bits
        if bits & HAT_LEFT:
            self.axes[first] = 1.0
        if bits & HAT_RIGHT:
            self.axes[first] = -1.0
        if bits & HAT_UP:
            self.axes[first + 1] = 1.0
        if bits & HAT_DOWN:
            self.axes[first + 1] = -1.0
        if not bits:
            self.axes[first] = self.axes[first + 1] = 0.0
        return True

    def settle(self, published: bool, now_ns: int) -> bool:
        """After a step's event (or its timeout): whether to publish, counting autorepeat and a pending axis."""
        if published:
            return True
        p = self.params
        due = p.autorepeat_rate_hz > 0.0 and (now_ns - self.last_repeat_ns) // 1_000_000 >= p.autorepeat_interval_ms
        if due or self.publish_soon:
            self.last_repeat_ns = now_ns
            self.publish_soon = False
            return True
        return False
