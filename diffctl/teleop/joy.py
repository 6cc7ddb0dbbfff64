"""The game pad teleop loop: events from a joy source → JoyState → JoyTeleop → velocity commands.

A source is anything with `axis_ranges`, `initial_events()` and `read(timeout_s)` returning
(type, code, value) events: the evdev device in production, a scripted list in tests.
"""

from __future__ import annotations

import threading
import time
from typing import Any, Protocol

from diffctl.teleop.joy_config import JoyParams
from diffctl.teleop.joy_mapping import AxisRange, Command, JoyState, JoyTeleop
from diffctl.teleop.linux_input import EV_SYN, SYN_DROPPED, SYN_REPORT
from diffctl.teleop.twist_command import TwistCommand


class JoySource(Protocol):
    @property
    def axis_ranges(self) -> dict[int, AxisRange]: ...

    def initial_events(self) -> list[tuple[int, int, int]]: ...

    def read(self, timeout_s: float | None) -> list[tuple[int, int, int]]: ...


def run_joy(
    source: JoySource, params: JoyParams, command: TwistCommand, stop: threading.Event, log: Any = None
) -> None:
    """Publish teleop_twist_joy's commands until `stop` is set; evaluated per input frame and at autorepeat_rate."""
    state = JoyState(source.axis_ranges, params.deadzone)
    state.apply_all(source.initial_events())
    teleop = JoyTeleop(params)
    period_s = 1.0 / params.autorepeat_rate_hz if params.autorepeat_rate_hz > 0 else None
    last: Command | None = None
    mode = ""

    def evaluate() -> None:
        nonlocal last, mode
        cmd = teleop.update(state)
        if teleop.mode != mode and log is not None:
            log.info(
                {
                    "normal": "enable button held: driving",
                    "turbo": "turbo button held: driving with turbo scales",
                    "idle": "not enabled" + (": sent one zero command" if cmd is not None else ""),
                }[teleop.mode]
            )
        mode = teleop.mode
        if cmd is not None:
            command.publish(cmd.linear_m_s, cmd.angular_rad_s)
            last = cmd

    try:
        evaluate()  # joy publishes once at start; teleop_twist_joy answers with its zero when not enabled
        next_repeat = time.monotonic() + (period_s or 0.0)
        while not stop.is_set():
            timeout = 0.25 if period_s is None else max(0.0, min(0.25, next_repeat - time.monotonic()))
            frame_done = False
            for ev_type, code, value in source.read(timeout):
                if ev_type == EV_SYN:
                    if code == SYN_DROPPED:
                        # The kernel buffer overflowed: events were lost, so re-read the whole state.
                        state.apply_all(source.initial_events())
                    frame_done = frame_done or code in (SYN_REPORT, SYN_DROPPED)
                else:
                    state.apply(ev_type, code, value)
            now = time.monotonic()
            repeat_due = period_s is not None and now >= next_repeat
            if frame_done or repeat_due:
                evaluate()
                if period_s is not None:
                    next_repeat = now + period_s
    finally:
        if last is not None and not last.is_zero:
            command.stop()
