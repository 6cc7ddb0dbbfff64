"""`LaunchContext`: the state a launch shares with every entity it visits."""

from __future__ import annotations

import asyncio
import os
from collections.abc import Callable, Iterable, MutableMapping
from typing import Any

from . import logging as launch_logging
from ._private.handler_index import HandlerIndex
from .event import Event
from .event_handler import BaseEventHandler
from .substitution import Substitution


class _LocalsView:
    """`context.locals`: the locals read as attributes; writing is refused."""

    def __init__(self, values: dict[str, Any]) -> None:
        object.__setattr__(self, '_values', values)

    def __getattr__(self, key: str) -> Any:
        values = object.__getattribute__(self, '_values')
        try:
            return values[key]
        except KeyError:
            listed = ', '.join(values)
            raise AttributeError(
                f"context.locals does not contain attribute '{key}', it contains: [{listed}]") from None

    def __setattr__(self, key: str, value: Any) -> None:
        raise AttributeError(f"can't set attribute '{key}', locals are read-only")


class _Saves:
    """Snapshots of one part of the context, taken and put back in last-in first-out order."""

    def __init__(self, label: str, take: Callable[[], Any], put_back: Callable[[Any], None]) -> None:
        self._label = label
        self._take = take
        self._put_back = put_back
        self._kept: list[Any] = []

    def save(self) -> None:
        self._kept.append(self._take())

    def restore(self) -> None:
        if not self._kept:
            raise RuntimeError(f'{self._label} stack unexpectedly empty')
        self._put_back(self._kept.pop())


def _set_process_environment(values: dict[str, str]) -> None:
    # os.environ must stay the same object: it writes through to the C environment children inherit
    os.environ.clear()
    os.environ.update(values)


class LaunchContext:
    """What the entities of a launch see and change while it runs.

    - `launch_configurations`: arguments and `let`s by name.
    - `environment`: the environment processes inherit, which is this process's `os.environ`.
    - `locals`: names given by whoever produced the entity being visited (an event handler gives
      `event`, an include `current_launch_file_path`, …); they last until that producer's scope ends.
      `extend_globals` gives names seen everywhere, from then on.
    - `emit_event` / `emit_event_sync` queue events for the LaunchService; `register_event_handler`
      adds a handler (ahead of the others, or behind them with `append=True`).
    - `asyncio_loop` while a LaunchService runs, `argv`, `noninteractive`, `is_shutdown`.
    """

    def __init__(self, *, argv: Iterable[str] | None = None, noninteractive: bool = False) -> None:
        self._argv = [] if argv is None else argv
        self._noninteractive = noninteractive
        self._ending = False
        self._loop: asyncio.AbstractEventLoop | None = None

        # used by the LaunchService: the event queue, the handlers, and futures the launch waits for
        self._queue: asyncio.Queue = asyncio.Queue()
        self._handlers = HandlerIndex()
        self._awaited: list[asyncio.Future] = []

        self._globals: dict[str, Any] = {}
        self._frame: dict[str, Any] = {}
        self._merged: dict[str, Any] | None = None  # globals under locals, made when asked for
        self._configurations: dict[str, str] = {}
        self._first_environment = os.environ.copy()

        self._saves = {
            'locals': _Saves('locals', lambda: dict(self._frame), self._set_frame),
            'environment': _Saves('environment', os.environ.copy, _set_process_environment),
            'launch_configurations': _Saves(
                'launch_configurations', lambda: self._configurations.copy(), self._set_configurations),
        }
        self._logger = None  # fetched when first needed: making it sets up the log files

    # ---- the run -------------------------------------------------------------------------------------------

    @property
    def argv(self):
        """The arguments the LaunchService was given."""
        return self._argv

    @property
    def noninteractive(self) -> bool:
        """No terminal: on shutdown, processes get their SIGINT from launch rather than from a terminal."""
        return self._noninteractive

    @property
    def is_shutdown(self) -> bool:
        """Whether the launch has begun to end (nothing new is started then)."""
        return self._ending

    @property
    def asyncio_loop(self) -> asyncio.AbstractEventLoop | None:
        """The loop running the launch; None while none does."""
        return self._loop

    def _running_on(self, loop: asyncio.AbstractEventLoop | None) -> None:
        self._loop = loop

    def _mark_ending(self) -> None:
        self._ending = True

    def add_completion_future(self, completion_future: asyncio.Future) -> None:
        """Keep the launch from counting as idle until `completion_future` is done."""
        self._awaited.append(completion_future)

    # ---- saving and restoring (Push*/Pop* actions, the LaunchService around each handler) ---------------

    def _save(self, part: str) -> None:
        self._saves[part].save()

    def _restore(self, part: str) -> None:
        self._saves[part].restore()

    def _restore_first_environment(self) -> None:
        _set_process_environment(self._first_environment)

    def _set_frame(self, frame: dict[str, Any]) -> None:
        self._frame = frame
        self._merged = None

    def _set_configurations(self, configurations: dict[str, str]) -> None:
        # the saved dict itself comes back: a reference taken inside the scope keeps the inner values
        self._configurations = configurations

    # ---- locals --------------------------------------------------------------------------------------------

    def extend_globals(self, extensions: dict[str, Any]) -> None:
        """Names seen in `locals` everywhere from now on (a local of the same name hides one)."""
        self._globals.update(extensions)
        self._merged = None

    def extend_locals(self, extensions: dict[str, Any]) -> None:
        """Names seen in `locals` until the current scope ends."""
        self._frame.update(extensions)
        self._merged = None

    def get_locals_as_dict(self) -> dict[str, Any]:
        """Globals and locals in one dictionary, locals winning."""
        if self._merged is None:
            self._merged = {**self._globals, **self._frame}
        return self._merged

    @property
    def locals(self) -> Any:
        """`get_locals_as_dict()` read as attributes: `context.locals.event`."""
        return _LocalsView(self.get_locals_as_dict())

    # ---- configurations and environment ----------------------------------------------------------------

    @property
    def launch_configurations(self) -> dict[str, str]:
        return self._configurations

    @property
    def environment(self) -> MutableMapping[str, str]:
        return os.environ

    # ---- events --------------------------------------------------------------------------------------------

    def register_event_handler(self, event_handler: BaseEventHandler, append: bool = False) -> None:
        """Add a handler, asked before those registered earlier — or after them, with `append`."""
        self._handlers.add(event_handler, append=append)

    def unregister_event_handler(self, event_handler: BaseEventHandler) -> None:
        """Remove a handler; ValueError when it is not registered."""
        self._handlers.remove(event_handler)

    def _handlers_for(self, event: Event) -> list[BaseEventHandler]:
        """The registered handlers that may take `event`, in the order they are offered it (a snapshot)."""
        return self._handlers.offered(event)

    def would_handle_event(self, event: Event) -> bool:
        """Whether some registered handler takes `event`."""
        return any(handler.matches(event) for handler in self._handlers_for(event))

    def _debug(self, message: str) -> None:
        if self._logger is None:
            self._logger = launch_logging.get_logger('launch.launch_context')
        self._logger.debug(message)

    def emit_event_sync(self, event: Event) -> None:
        """Queue `event` without waiting (on the loop's thread, or before the launch runs)."""
        self._debug(f"emitting event synchronously: '{event.name}'")
        self._queue.put_nowait(event)

    async def emit_event(self, event: Event) -> None:
        """Queue `event`."""
        self._debug(f"emitting event: '{event.name}'")
        await self._queue.put(event)

    def perform_substitution(self, substitution: Substitution) -> str:
        """What `substitution` stands for in this context."""
        return substitution.perform(self)
