"""The registered event handlers, found per event without asking every handler of a large launch.

A launch of N processes registers a few handlers per process, each taking events about its own process only.
Asking all of them about every process's start, exit, output and signals made a launch of N processes cost N²
matcher calls. Here a handler may say which event classes it can take (`_event_kinds`, see
`event_handler._takes_only`) and which one action they must be about (`_only_about`); an event about one action
is offered to the handlers of its class that concern no action in particular plus those concerning it, in the
order the context offers handlers (newest first, `append=True` ones last). Anything else gets every handler of
its class, as before.
"""

from __future__ import annotations

import heapq
from collections import deque
from collections.abc import Hashable
from operator import itemgetter
from typing import Any

from ..event_handler import BaseEventHandler, _may_take
from ..events.process.process_targeted_event import ProcessTargetedEvent
from ..events.process.running_process_event import RunningProcessEvent

_Pair = tuple[int, BaseEventHandler]  # (place in the offering order, handler)
_place = itemgetter(0)


def about_action(action: Any) -> Hashable:
    """What an OnActionEventBase for `action` and the events of a process action run by `action` concern."""
    return ('action', id(action))


def addressed_to(action: Any) -> Hashable | None:
    """What a ShutdownProcess/SignalProcess handler of `action` and events for `matches_action(action)` concern;
    None when `action ==` is not `is` (its class defines its own equality)."""
    return ('process', id(action)) if type(action).__eq__ is object.__eq__ else None


def _event_concerns(event: Any) -> Hashable | None:
    process_event = isinstance(event, RunningProcessEvent)
    if isinstance(event, ProcessTargetedEvent):
        if process_event:
            return None
        target = getattr(event.process_matcher, '_target_action', None)
        return None if target is None else addressed_to(target)
    return about_action(event.action) if process_event else None


def _concern_of(handler: BaseEventHandler) -> Hashable | None:
    if type(handler).matches is not BaseEventHandler.matches:
        return None  # a matcher of its own: it is asked
    concern = getattr(handler, '_only_about', None)
    return concern if type(concern) is tuple else None  # what about_action / addressed_to gave, nothing else


def _with(pairs: list[_Pair], pair: _Pair) -> list[_Pair]:
    # a new list: one handed out stays the snapshot it was
    return [*pairs, pair] if pair[0] > 0 else [pair, *pairs]


def _without(pairs: list[_Pair], handler: BaseEventHandler) -> list[_Pair]:
    kept = list(pairs)
    for i, (_, registered) in enumerate(kept):
        if registered is handler:
            del kept[i]
            break
    return kept


class HandlerIndex:
    """Handlers in offering order (`handlers`), and `offered(event)`: those that may take `event`."""

    def __init__(self) -> None:
        self.handlers: deque[BaseEventHandler] = deque()
        self._first = 0  # places: prepended handlers count down from 0, appended ones up
        self._last = 0
        self._general: list[_Pair] = []  # handlers concerning no one action
        self._by_concern: dict[Hashable, list[_Pair]] = {}
        self._general_of: dict[type, list[_Pair]] = {}  # per event class seen: the general handlers it may go to
        self._offered_all: dict[type, list[BaseEventHandler]] = {}  # per event class: for events of no concern
        self._offered_to: dict[type, dict[Hashable, list[BaseEventHandler]]] = {}

    def add(self, handler: BaseEventHandler, *, append: bool) -> None:
        if append:
            self._last += 1
            pair = (self._last, handler)
            self.handlers.append(handler)
        else:
            self._first -= 1
            pair = (self._first, handler)
            self.handlers.appendleft(handler)
        concern = _concern_of(handler)
        if concern is None:
            self._general = _with(self._general, pair)
        else:
            self._by_concern[concern] = _with(self._by_concern.get(concern, []), pair)
        self._changed(handler, concern, lambda pairs: _with(pairs, pair))

    def remove(self, handler: BaseEventHandler) -> None:
        self.handlers.remove(handler)  # ValueError when it is not registered
        concern = _concern_of(handler)
        if concern is None:
            self._general = _without(self._general, handler)
        else:
            kept = _without(self._by_concern[concern], handler)
            if kept:
                self._by_concern[concern] = kept
            else:
                del self._by_concern[concern]
        self._changed(handler, concern, lambda pairs: _without(pairs, handler))

    def _changed(self, handler: BaseEventHandler, concern: Hashable | None, edit: Any) -> None:
        for kind in list(self._general_of):
            if not _may_take(handler, kind):
                continue
            self._offered_all.pop(kind, None)
            if concern is None:
                self._general_of[kind] = edit(self._general_of[kind])
                self._offered_to.pop(kind, None)
            else:
                self._offered_to.get(kind, {}).pop(concern, None)

    def offered(self, event: Any) -> list[BaseEventHandler]:
        """The handlers that may take `event`, in offering order (a list never changed afterwards)."""
        kind = type(event)
        general = self._general_of.get(kind)
        if general is None:
            general = self._general_of[kind] = [pair for pair in self._general if _may_take(pair[1], kind)]
        concern = _event_concerns(event)
        if concern is None:
            found = self._offered_all.get(kind)
            if found is None:
                pairs = general + [
                    pair for pairs in self._by_concern.values() for pair in pairs if _may_take(pair[1], kind)]
                pairs.sort(key=_place)
                found = self._offered_all[kind] = [handler for _, handler in pairs]
            return found
        per_concern = self._offered_to.setdefault(kind, {})
        found = per_concern.get(concern)
        if found is None:
            own = [pair for pair in self._by_concern.get(concern, ()) if _may_take(pair[1], kind)]
            pairs = heapq.merge(general, own, key=_place) if own else general
            found = per_concern[concern] = [handler for _, handler in pairs]
        return found
