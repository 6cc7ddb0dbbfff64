"""rclpy.waitable.Waitable: the base of entities an executor runs besides the node's own (actions, events).

A subclass keeps its own ready state, says whether it has work in `is_ready(wait_set)` (the argument is
always None here: there is no rcl wait set), hands it over in `take_data()` and runs it in
`async execute(data)`. Whatever makes it ready from another thread must call `diffctl.client.waiting.notify()`
so a sleeping executor looks again.
"""

from __future__ import annotations

from typing import Any

from diffctl.client.task import Future


class NumberOfEntities:
    def __init__(self, num_subs: int = 0, num_gcs: int = 0, num_timers: int = 0, num_clients: int = 0,
                 num_services: int = 0, num_events: int = 0) -> None:
        self.num_subscriptions = num_subs
        self.num_guard_conditions = num_gcs
        self.num_timers = num_timers
        self.num_clients = num_clients
        self.num_services = num_services
        self.num_events = num_events

    def __add__(self, other: NumberOfEntities) -> NumberOfEntities:
        return NumberOfEntities(
            self.num_subscriptions + other.num_subscriptions,
            self.num_guard_conditions + other.num_guard_conditions, self.num_timers + other.num_timers,
            self.num_clients + other.num_clients, self.num_services + other.num_services,
            self.num_events + other.num_events)


class Waitable:
    def __init__(self, callback_group: Any) -> None:
        self.callback_group = callback_group
        self.callback_group.add_entity(self)
        self._executor_event = False
        self._futures: list[Future] = []

    def __enter__(self) -> Waitable:
        return self

    def __exit__(self, *exc: Any) -> None:
        pass

    def add_future(self, future: Future) -> None:
        self._futures.append(future)

    def remove_future(self, future: Future) -> None:
        self._futures.remove(future)

    def is_ready(self, wait_set: Any = None) -> bool:
        raise NotImplementedError("Must be implemented by subclass")

    def take_data(self) -> Any:
        raise NotImplementedError("Must be implemented by subclass")

    async def execute(self, taken_data: Any) -> None:
        raise NotImplementedError("Must be implemented by subclass")

    def get_num_entities(self) -> NumberOfEntities:
        return NumberOfEntities()

    def add_to_wait_set(self, wait_set: Any) -> None:
        pass

    def destroy(self) -> None:
        pass

    def _due_in_s(self) -> float | None:
        """Seconds until this waitable becomes ready on its own (a timeout), or None: only notify() tells."""
        return None
