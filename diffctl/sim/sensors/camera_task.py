"""The stepper task of one camera-type sensor: render on demand, publish what is subscribed, keep up or slow down.

Runs on the sim thread at the sensor's period of sim time. Nobody subscribed: nothing at all. Only
camera_info subscribed: camera_info, no render. Otherwise one render feeds every subscribed output; its wall
time (render, derive, encode) is measured, and when that cannot fit the requested rate at the current
real-time factor (rate.py) the task's period grows and a warning naming the sensor is logged once. The
render still happens on the sim thread (PyBullet is single-threaded), so the slower rate is what keeps a
camera from holding the physics back.

A triggered camera (`<triggered>true</triggered>`, gz-sensors CameraSensor) renders at its tick only after a
message on its trigger topic (default `<image topic>/trigger`, gz.msgs.Boolean, value ignored); several
triggers between two ticks give one frame, and a trigger waits while nobody is subscribed.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from diffctl.sim.sensors.camera_sensor import CameraSensor
from diffctl.sim.sensors.rate import RenderRate
from diffctl.sim.stepper import Task
from diffctl.sim.transport import GzPublisher


class CameraTask:
    def __init__(
        self,
        sensor: CameraSensor,
        publishers: dict[str, GzPublisher],
        rate: RenderRate,
        rtf: Callable[[], float],
        warn: Callable[[str], None],
    ) -> None:
        self.sensor, self.publishers, self.rate, self.rtf, self.warn = sensor, publishers, rate, rtf, warn
        self.task: Task | None = None  # set once the stepper has it, so a lowered rate can change its period
        self._warned = False
        self.triggered = False  # set for a triggered camera: frames only on trigger
        self.pending = False

    def trigger(self) -> None:
        self.pending = True

    def __call__(self, sim_time_ns: int) -> None:
        if self.triggered and not self.pending:
            return
        wanted = {name for name, pub in self.publishers.items() if pub.matched}
        if not wanted:
            return
        self.pending = False
        rendering = self.sensor.needs_render(wanted)
        t0 = time.perf_counter()
        for name, msg in self.sensor.messages(sim_time_ns, wanted).items():
            self.publishers[name].publish(msg)
        if not rendering:
            return
        rtf = self.rtf()
        period_ns = self.rate.observe(time.perf_counter() - t0, rtf)
        if period_ns is None:
            return
        if self.task is not None:
            self.task.period_ns = period_ns
        if not self._warned:
            self._warned = True
            s = self.sensor
            self.warn(
                f"{s.kind} {s.name}: rendering {s.width}x{s.height} on the CPU cannot keep "
                f"{1e9 / self.rate.requested_period_ns:g} Hz at real-time factor {rtf:g}; "
                f"publishing at {1e9 / period_ns:.3g} Hz instead"
            )
