"""joy_linux_node's message state, pure: js_event records in, the Joy axes/buttons and when to publish out.

Axes are the kernel's values (-32767..32767) with the deadzone cut out smoothly, scaled to [-1, 1] and negated;
the message grows to the highest axis or button number seen. A button change publishes at once. An axis change
(and the kernel's initial-state records) start a coalescing timer, and the message goes when it runs out; with
nothing going on, autorepeat_rate resends it. One timer serves both, as the node's one select() timeout: it
keeps running across events until it fires or a publication clears it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from diffctl.joy.linux_joystick import JS_EVENT_AXIS, JS_EVENT_BUTTON, JsEvent

AXIS_MAX = 32767
IDLE_WAIT_NS = 1_000_000_000


@dataclass(frozen=True)
class LinuxJoyParams:
    deadzone: float = 0.05
    autorepeat_rate_hz: float = 20.0
    coalesce_interval_s: float = 0.001
    default_trig_val: bool = False
    sticky_buttons: bool = False


def corrected(deadzone: float, autorepeat_rate_hz: float, coalesce_interval_s: float,
              default_trig_val: bool, sticky_buttons: bool) -> tuple[LinuxJoyParams, list[str]]:
    """The node's corrections of out-of-range values, each with the warning it logs."""
    warnings = []
    if coalesce_interval_s != 0 and autorepeat_rate_hz > 1 / coalesce_interval_s:
        warnings.append(f"joy_linux_node: autorepeat_rate ({autorepeat_rate_hz:f} Hz) > 1/coalesce_interval "
                        f"({1 / coalesce_interval_s:f} Hz) does not make sense. Timing behavior is not well defined.")
    if deadzone >= 1:
        warnings.append("joy_linux_node: deadzone greater than 1 was requested. The semantics of deadzone have "
                        "changed. It is now related to the range [-1:1] instead of [-32767:32767]. For now I am "
                        "dividing your deadzone by 32767, but this behavior is deprecated so you need to update "
                        "your launch file.")
        deadzone /= AXIS_MAX
    if deadzone > 0.9:
        warnings.append(f"joy_node: deadzone ({deadzone:f}) greater than 0.9, setting it to 0.9")
        deadzone = 0.9
    if deadzone < 0:
        warnings.append(f"joy_node: deadzone_ ({deadzone:f}) less than 0, setting to 0.")
        deadzone = 0.0
    if autorepeat_rate_hz < 0:
        warnings.append(f"joy_node: autorepeat_rate ({autorepeat_rate_hz:f}) less than 0, setting to 0.")
        autorepeat_rate_hz = 0.0
    if coalesce_interval_s < 0:
        warnings.append(f"joy_node: coalesce_interval ({coalesce_interval_s:f}) less than 0, setting to 0.")
        coalesce_interval_s = 0.0
    return LinuxJoyParams(deadzone, autorepeat_rate_hz, coalesce_interval_s, default_trig_val,
                          sticky_buttons), warnings


def axis_value(raw: int, deadzone: float) -> float:
    cut = AXIS_MAX * deadzone
    if raw > cut:
        shifted = raw - cut
    elif raw < -cut:
        shifted = raw + cut
    else:
        shifted = 0.0
    return shifted * (-1.0 / (1.0 - deadzone) / AXIS_MAX) + 0.0


def _seconds_ns(seconds: float) -> int:
    # select()'s timeval: whole seconds, then microseconds truncated
    whole = math.trunc(seconds)
    return whole * 1_000_000_000 + int((seconds - whole) * 1e6) * 1000


class LinuxJoyState:
    """The message and the node's one timer. Times are monotonic nanoseconds."""

    def __init__(self, params: LinuxJoyParams, now_ns: int) -> None:
        self.params = params
        self.axes: list[float] = []
        self.buttons: list[int] = []
        self.deadline_ns = now_ns + IDLE_WAIT_NS
        self.timer_set = False
        self.pending = False
        self.unknown: list[JsEvent] = []

    def wait_s(self, now_ns: int) -> float:
        return max(0, self.deadline_ns - now_ns) / 1e9

    def _apply(self, event: JsEvent) -> tuple[bool, bool]:
        """(publish now, publish soon) for one record."""
        p, n = self.params, event.number
        if event.kind == JS_EVENT_BUTTON:
            if n >= len(self.buttons):
                self.buttons.extend([0] * (n + 1 - len(self.buttons)))
            if p.sticky_buttons:
                if event.value == 1:
                    self.buttons[n] = 1 - self.buttons[n]
            else:
                self.buttons[n] = 1 if event.value else 0
            return (False, True) if event.is_init else (True, False)
        if event.kind == JS_EVENT_AXIS:
            if n >= len(self.axes):
                self.axes.extend([0.0] * (n + 1 - len(self.axes)))
            # The initial-state records of axes are only taken with default_trig_val (a released trigger
            # reads as its true value instead of 0 until first moved).
            if p.default_trig_val or not event.is_init:
                self.axes[n] = axis_value(event.value, p.deadzone)
            return False, True
        self.unknown.append(event)
        return False, False

    def step(self, event: JsEvent | None, now_ns: int) -> bool:
        """One record (None: the timer ran out) → whether to publish now."""
        if event is not None:
            publish_now, publish_soon = self._apply(event)
        else:
            publish_now, publish_soon = self.timer_set, False
        if publish_now:
            self.timer_set = self.pending = publish_soon = False
        if not self.pending and publish_soon:
            self.deadline_ns = now_ns + _seconds_ns(self.params.coalesce_interval_s)
            self.pending = self.timer_set = True
        if not self.timer_set and self.params.autorepeat_rate_hz > 0:
            self.deadline_ns = now_ns + _seconds_ns(1 / self.params.autorepeat_rate_hz)
            self.timer_set = True
        if not self.timer_set:
            self.deadline_ns = now_ns + IDLE_WAIT_NS
        return publish_now
