"""rclpy.timer: Timer (ready when its clock reaches the next call; run by an executor) and Rate."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from diffctl.client import waiting
from diffctl.client.clock import Clock, ClockType, JumpThreshold
from diffctl.client.destroyable import Handle, handle_of
from diffctl.client.duration import Duration
from diffctl.client.exceptions import InvalidHandle, ROSInterruptException


async def await_or_execute(callback: Callable[..., Any], *args: Any) -> Any:
    """Run a callback, awaiting it when it is a coroutine function (rclpy's coroutine callbacks)."""
    import inspect

    if inspect.iscoroutinefunction(callback):
        return await callback(*args)
    return callback(*args)


class Timer:
    def __init__(self, callback: Callable[[], Any] | None, callback_group: Any, timer_period_ns: int, clock: Clock,
                 *, context: Any = None, autostart: bool = True) -> None:
        self._clock = clock
        self._context = context
        self.callback = callback
        self.callback_group = callback_group
        self._executor_event = False
        self._period_ns = int(timer_period_ns)
        self._lock = threading.Lock()
        now = clock.now_ns()
        self._last_call_ns = now
        self._next_call_ns = now + self._period_ns
        self._canceled = not autostart
        self._destroyed = False
        self._node: Any = None
        self._credit_ns = 0
        self._jump_handle: Any = None
        if clock.clock_type == ClockType.ROS_TIME:
            # rcl's timers on ROS time: across a switch to or from ROS time they keep their remaining time; a
            # jump back past their last call restarts the period from the new time.
            self._jump_handle = clock.create_jump_callback(
                JumpThreshold(min_forward=Duration(nanoseconds=1), min_backward=Duration(nanoseconds=-1),
                              on_clock_change=True),
                pre_callback=self._before_jump, post_callback=self._after_jump)

    def _before_jump(self) -> None:
        now = self._clock.now_ns()
        with self._lock:
            # Only a switch of time source uses the credit; with the clock still at zero there is none.
            self._credit_ns = max(0, self._next_call_ns - now) if now else 0

    def _after_jump(self, jump: Any) -> None:
        from diffctl.client.clock import ClockChange

        now = self._clock.now_ns()
        with self._lock:
            if jump.clock_change in (ClockChange.ROS_TIME_ACTIVATED, ClockChange.ROS_TIME_DEACTIVATED):
                credit, self._credit_ns = self._credit_ns, 0
                if now and credit:
                    self._next_call_ns = now + credit
                    self._last_call_ns = self._next_call_ns - self._period_ns
            elif now < self._last_call_ns:
                self._next_call_ns = now + self._period_ns
                self._last_call_ns = now
            elif now < self._next_call_ns:
                # Time moved on but not to this timer's call: nothing for an executor to do (rcl's timers
                # trigger their guard condition only once they are due). A simulator sets the time every step.
                return
        waiting.notify()

    @property
    def handle(self) -> Handle:
        return handle_of(self)

    def _check(self) -> None:
        # rclpy's timer methods each enter the rcl timer's handle: a destroyed timer answers nothing.
        if self._destroyed:
            raise InvalidHandle("cannot use Destroyable because destruction was requested")

    @property
    def clock(self) -> Clock:
        return self._clock

    @property
    def timer_period_ns(self) -> int:
        self._check()
        return self._period_ns

    @timer_period_ns.setter
    def timer_period_ns(self, value: int) -> None:
        self._check()
        with self._lock:
            self._next_call_ns = self._last_call_ns + int(value)
            self._period_ns = int(value)
        waiting.notify()

    def _ready(self) -> bool:
        return not self._canceled and not self._destroyed and self._clock.now_ns() >= self._next_call_ns

    def is_ready(self) -> bool:
        self._check()
        return self._ready()

    def _due_in_s(self) -> float | None:
        """Seconds of wall time to wait before this timer may be ready (None: only a clock update tells)."""
        if self._canceled or self._destroyed:
            return None
        if getattr(self._clock, "_ros_time_active", False):
            return None
        return max(0.0, (self._next_call_ns - self._clock.now_ns()) / 1e9)

    def is_canceled(self) -> bool:
        self._check()
        return self._canceled

    def cancel(self) -> None:
        self._check()
        self._canceled = True

    def reset(self) -> None:
        self._check()
        with self._lock:
            now = self._clock.now_ns()
            self._next_call_ns = now + self._period_ns
            self._canceled = False
        waiting.notify()

    def time_since_last_call(self) -> int:
        self._check()
        return self._clock.now_ns() - self._last_call_ns

    def time_until_next_call(self) -> int | None:
        self._check()
        if self._canceled:
            return None
        return self._next_call_ns - self._clock.now_ns()

    def _call(self) -> None:
        """rcl_timer_call: the next call a period on, skipping the periods already missed."""
        with self._lock:
            now = self._clock.now_ns()
            self._last_call_ns = now
            nxt = self._next_call_ns + self._period_ns
            if nxt < now:
                if self._period_ns == 0:
                    nxt = now
                else:
                    ahead = now - nxt
                    nxt += (1 + (ahead - 1) // self._period_ns) * self._period_ns
            self._next_call_ns = nxt

    def _take(self) -> Callable[[], Any] | None:
        if self._destroyed:
            return None
        self._call()
        callback = self.callback

        async def _execute() -> None:
            if callback is not None:
                await await_or_execute(callback)

        return _execute

    def destroy(self) -> None:
        if self._node is not None:
            self._node.destroy_timer(self)
        else:
            self._destroy()

    def _destroy(self) -> None:
        self._destroyed = True
        if self._jump_handle is not None:
            self._jump_handle.unregister()
            self._jump_handle = None


class Rate:
    """Sleeps until its timer next fires; another thread must spin the node, as with rclpy's Rate."""

    def __init__(self, timer: Timer, *, context: Any) -> None:
        self._timer = timer
        # Timer fires so far, and the count the last sleeper woke to: a fire nobody slept through yet ends the
        # next sleep at once, so a loop whose work overran the period keeps the rate, as with rclpy's Rate.
        self._ticks = 0
        self._ticks_slept = 0
        self._wake = threading.Condition()
        self._is_shutdown = False
        self._is_destroyed = False
        timer.callback = self._tick
        context.on_shutdown(self._on_shutdown)

    def _tick(self) -> None:
        with self._wake:
            self._ticks += 1
            self._wake.notify_all()

    def _on_shutdown(self) -> None:
        self._is_shutdown = True
        self.destroy()

    def destroy(self) -> None:
        with self._wake:
            self._is_destroyed = True
            self._wake.notify_all()

    def sleep(self) -> None:
        if self._is_shutdown:
            raise ROSInterruptException()
        if self._is_destroyed:
            raise RuntimeError("Rate cannot sleep because it has been destroyed")
        if self._timer._destroyed:
            self.destroy()
            raise InvalidHandle("Rate cannot sleep because the timer has been destroyed")
        with self._wake:
            slept = self._ticks_slept
            self._wake.wait_for(lambda: self._ticks != slept or self._is_destroyed)
            self._ticks_slept = self._ticks
        if self._is_shutdown:
            raise ROSInterruptException()
