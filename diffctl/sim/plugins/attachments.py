"""What a system attached to the world: its per-step hooks, its periodic tasks and its gz-transport endpoints,
kept so that `close` (the model removed, the sim stopping) takes back exactly those and nothing else."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.sim.plugins.base import PluginContext
from diffctl.sim.stepper import Task


class Attachments:
    def __init__(self, ctx: PluginContext) -> None:
        self._ctx = ctx
        self._hooks: list[Callable[[], None]] = []
        self._tasks: list[Task] = []
        self._endpoints: list[Any] = []

    def each_step(self, hook: Callable[[], None]) -> None:
        """`hook()` before every physics step."""
        self._ctx.stepper.step_hooks.append(hook)
        self._hooks.append(hook)

    def every(self, name: str, period_ns: int, fn: Callable[[int], None]) -> Task:
        """`fn(sim_time_ns)` every `period_ns` of sim time from now."""
        task = self._ctx.stepper.add_task(name, period_ns, fn)
        self._tasks.append(task)
        return task

    def subscribe(self, topic: str, gz_type: str, handler: Callable[[dict[str, Any]], None]) -> Any:
        """A gz-transport subscription (None when the world runs without a bus)."""
        t = self._ctx.transport
        if t is None:
            return None
        sub = t.subscribe(topic, gz_type, handler)
        self._endpoints.append(sub)
        return sub

    def publisher(self, topic: str, gz_type: str) -> Any:
        """A gz-transport publisher (None when the world runs without a bus)."""
        t = self._ctx.transport
        if t is None:
            return None
        pub = t.publisher(topic, gz_type)
        self._endpoints.append(pub)
        return pub

    def close(self) -> None:
        stepper = self._ctx.stepper
        for hook in self._hooks:
            if hook in stepper.step_hooks:
                stepper.step_hooks.remove(hook)
        for task in self._tasks:
            stepper.remove_task(task)
        t = self._ctx.transport
        if t is not None:
            for endpoint in self._endpoints:
                t.release(endpoint)
        self._hooks, self._tasks, self._endpoints = [], [], []
