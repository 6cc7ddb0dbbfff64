"""rclpy.clock: system, steady and ROS clocks, ROS time overrides (sim time) and time-jump callbacks."""

from __future__ import annotations

import enum
import threading
import time
from collections.abc import Callable
from typing import Any

from diffctl.client import waiting
from diffctl.client.clock_type import ClockType
from diffctl.client.duration import Duration
from diffctl.client.exceptions import NotInitializedException
from diffctl.client.ros_time import Time


class ClockChange(enum.IntEnum):
    ROS_TIME_NO_CHANGE = 1
    ROS_TIME_ACTIVATED = 2
    ROS_TIME_DEACTIVATED = 3
    SYSTEM_TIME_NO_CHANGE = 4


class JumpThreshold:
    def __init__(self, *, min_forward: Duration | None, min_backward: Duration | None,
                 on_clock_change: bool = True) -> None:
        if min_forward is not None and min_forward.nanoseconds <= 0:
            raise ValueError("min_forward must be a positive non-zero duration")
        if min_backward is not None and min_backward.nanoseconds >= 0:
            raise ValueError("min_backward must be a negative non-zero duration")
        if min_forward is None and min_backward is None and not on_clock_change:
            raise ValueError("At least one jump threshold must be enabled")
        self.min_forward = min_forward
        self.min_backward = min_backward
        self.on_clock_change = on_clock_change


class TimeJump:
    def __init__(self, clock_change: ClockChange, delta: Duration) -> None:
        if not isinstance(clock_change, ClockChange):
            raise TypeError("clock_change must be an instance of rclpy.clock.ClockChange")
        self._clock_change = clock_change
        self._delta = delta

    @property
    def clock_change(self) -> ClockChange:
        return self._clock_change

    @property
    def delta(self) -> Duration:
        return self._delta


class JumpHandle:
    def __init__(self, *, clock: Clock, threshold: JumpThreshold, pre_callback: Callable[[], None] | None,
                 post_callback: Callable[[TimeJump], None] | None) -> None:
        if pre_callback is None and post_callback is None:
            raise ValueError("One of pre_callback or post_callback must be callable")
        if pre_callback is not None and not callable(pre_callback):
            raise ValueError("pre_callback must be callable if given")
        if post_callback is not None and not callable(post_callback):
            raise ValueError("post_callback must be callable if given")
        self._clock: Clock | None = clock
        self.threshold = threshold
        self.pre_callback = pre_callback
        self.post_callback = post_callback
        with clock._lock:
            clock._jump_handles.append(self)

    def unregister(self) -> None:
        clock, self._clock = self._clock, None
        if clock is not None:
            with clock._lock:
                if self in clock._jump_handles:
                    clock._jump_handles.remove(self)

    def __enter__(self) -> JumpHandle:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.unregister()

    def _wants(self, change: ClockChange, delta_ns: int) -> bool:
        th = self.threshold
        if change in (ClockChange.ROS_TIME_ACTIVATED, ClockChange.ROS_TIME_DEACTIVATED):
            return th.on_clock_change
        if th.min_forward is not None and delta_ns >= th.min_forward.nanoseconds:
            return True
        return th.min_backward is not None and delta_ns <= th.min_backward.nanoseconds


class Clock:
    def __new__(cls, *, clock_type: ClockType = ClockType.SYSTEM_TIME) -> Clock:
        if not isinstance(clock_type, ClockType):
            raise TypeError("Clock type must be a ClockType enum")
        self = super().__new__(ROSClock if clock_type is ClockType.ROS_TIME else cls)
        self._clock_type = clock_type
        self._lock = threading.RLock()
        self._cond = threading.Condition(self._lock)
        self._jump_handles: list[JumpHandle] = []
        self._ros_time_active = False
        self._override_ns = 0
        self._sleepers = 0  # threads in sleep_until, waiting on _cond
        return self

    @property
    def clock_type(self) -> ClockType:
        return self._clock_type

    @property
    def handle(self) -> Clock:
        return self

    def __enter__(self) -> Clock:
        return self

    def __exit__(self, *exc: Any) -> None:
        pass

    def __repr__(self) -> str:
        return f"Clock(clock_type={self._clock_type.name})"

    def now_ns(self) -> int:
        if self._clock_type is ClockType.STEADY_TIME:
            return time.monotonic_ns()
        if self._clock_type is ClockType.ROS_TIME and self._ros_time_active:
            return self._override_ns
        return time.time_ns()

    def now(self) -> Time:
        return Time(nanoseconds=self.now_ns(), clock_type=self._clock_type)

    def create_jump_callback(self, threshold: JumpThreshold, *, pre_callback: Callable[[], None] | None = None,
                             post_callback: Callable[[TimeJump], None] | None = None) -> JumpHandle:
        return JumpHandle(clock=self, threshold=threshold, pre_callback=pre_callback, post_callback=post_callback)

    def _jump_handles_for(self, change: ClockChange, delta_ns: int) -> list[JumpHandle]:
        with self._lock:
            return [h for h in self._jump_handles if h._wants(change, delta_ns)]

    def _pre_jump(self, handles: list[JumpHandle]) -> None:
        for h in handles:
            if h.pre_callback is not None:
                h.pre_callback()

    def _post_jump(self, handles: list[JumpHandle], change: ClockChange, delta_ns: int) -> None:
        for h in handles:
            if h.post_callback is not None:
                h.post_callback(TimeJump(change, Duration(nanoseconds=delta_ns)))

    def sleep_until(self, until: Time, context: Any = None) -> bool:
        """Block until this clock reaches `until`; False on shutdown or when ROS time is switched on or off."""
        from diffctl.client.context import get_default_context

        context = get_default_context() if context is None else context
        if not context.ok():
            raise NotInitializedException()
        if until.clock_type != self._clock_type:
            raise ValueError("until's clock type does not match this clock's type")
        with self._lock:
            active = self._ros_time_active
        woke = threading.Event()

        def wake() -> None:
            woke.set()
            with self._cond:
                self._cond.notify_all()

        context.on_shutdown(wake)
        while context.ok():
            with self._cond:
                if self._ros_time_active != active:
                    return False
                now = self.now_ns()
                if now >= until.nanoseconds:
                    return True
                self._sleepers += 1
                try:
                    if self._ros_time_active:
                        self._cond.wait(0.1)
                    else:
                        self._cond.wait(min((until.nanoseconds - now) / 1e9, 0.1))
                finally:
                    self._sleepers -= 1
        return False

    def sleep_for(self, rel_time: Duration, context: Any = None) -> bool:
        return self.sleep_until(self.now() + rel_time, context)


class ROSClock(Clock):
    def __new__(cls) -> ROSClock:
        return Clock.__new__(Clock, clock_type=ClockType.ROS_TIME)  # type: ignore[return-value]

    @property
    def ros_time_is_active(self) -> bool:
        return self._ros_time_active

    def _set_ros_time_is_active(self, enabled: bool) -> None:
        if self._ros_time_active == enabled:
            return
        change = ClockChange.ROS_TIME_ACTIVATED if enabled else ClockChange.ROS_TIME_DEACTIVATED
        handles = self._jump_handles_for(change, 0)
        self._pre_jump(handles)  # before the switch: callbacks see the time they are leaving
        with self._cond:
            self._ros_time_active = enabled
            self._cond.notify_all()
        self._post_jump(handles, change, 0)
        waiting.notify()

    def set_ros_time_override(self, time: Time) -> None:
        if not isinstance(time, Time):
            raise TypeError(f"Time must be specified as rclpy.time.Time. Received type: {type(time)}")
        self._set_override_ns(time.nanoseconds)

    def set_ros_time_override_ns(self, ns: int) -> None:
        """set_ros_time_override from an int of nanoseconds, without a Time to build and check (diffctl's
        addition, for a host setting its nodes' clocks every cycle)."""
        self._set_override_ns(ns)

    def _set_override_ns(self, ns: int) -> None:
        if not self._jump_handles:
            # Nobody to tell of the jump (the usual clock; a simulator sets its hosted controllers' clocks every
            # cycle): the store, and a wake-up only when a sleep_until waits on this clock.
            with self._lock:
                self._override_ns = ns
                if self._sleepers:
                    self._cond.notify_all()
            return
        delta = ns - self._override_ns
        handles = self._jump_handles_for(ClockChange.ROS_TIME_NO_CHANGE, delta) if self._ros_time_active else []
        self._pre_jump(handles)
        with self._cond:
            self._override_ns = ns
            active = self._ros_time_active
            self._cond.notify_all()
        if active:
            # Executors are woken by what the new time makes ready (a timer's jump callback, once it is due),
            # not by every update: with /clock at 1 kHz, or a simulator setting the time of its hosted
            # controllers' clocks every cycle, they would wake for nothing each time.
            self._post_jump(handles, ClockChange.ROS_TIME_NO_CHANGE, delta)
