"""`event_named`: a matcher on the kind of event."""

from __future__ import annotations

from collections.abc import Callable

from ..event import Event


def event_named(name: str) -> Callable[[Event], bool]:
    """A matcher for `EventHandler`: true for the events whose `name` is `name`."""

    def named(event: Event) -> bool:
        return event.name == name

    return named
