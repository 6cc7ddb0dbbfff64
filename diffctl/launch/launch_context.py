"""`LaunchContext`: the state a launch shares with every entity it visits."""

from __future__ import annotations

import asyncio
import collections
import os
from collections.abc import Iterable, MutableMapping
from typing import Any

from . import logging as launch_logging
from .event import Event
from .event_handler import BaseEventHandler
from .substitution import Substitution


class _ReadOnlyLocals:
    """`context.locals`: the locals dictionary read as attributes (`context.locals.event`)."""

    def __init__(self, values: dict[str, Any]) -> None:
        object.__setattr__(self, '_values', values)

    def __getattr__(self, key: str) -> Any:
        values = object.__getattribute__(self, '_values')
        if key not in values:
            raise AttributeError(
                "context.locals does not contain attribute '{}', it contains: [{}]".format(
                    key, ', '.join(values.keys())))
        return values[key]

    def __setattr__(self, key: str, value: Any) -> None:
        raise AttributeError(f"can't set attribute '{key}', locals are read-only")


class LaunchContext:
    """What entities see while a launch runs.

    - `locals`: variables set by whoever yielded the entity (an event handler sets `event`, an include
      sets `current_launch_file_path`, …); they are scoped to the entities being yielded, `globals`
      (set with `extend_globals`) are seen everywhere.
    - `launch_configurations`: the launch arguments and `let`s, by name.
    - `environment`: this process's environment (`os.environ`), which processes inherit.
    - events: `emit_event` queues one for the service; `register_event_handler` adds a handler.
    - `asyncio_loop` while the service runs, `argv`, `noninteractive`, `is_shutdown`.
    """

    def __init__(self, *, argv: Iterable[str] | None = None, noninteractive: bool = False) -> None:
        self.__argv = argv if argv is not None else []
        self.__noninteractive = noninteractive

        self._event_queue: asyncio.Queue = asyncio.Queue()
        self._event_handlers: collections.deque = collections.deque()
        self._completion_futures: list[asyncio.Future] = []

        self.__globals: dict[str, Any] = {}
        self.__locals: dict[str, Any] = {}
        self.__locals_stack: list[dict[str, Any]] = []
        self.__combined: dict[str, Any] | None = None

        self.__launch_configurations: dict[str, str] = {}
        self.__launch_configurations_stack: list[dict[str, str]] = []

        self.__environment_stack: list[dict[str, str]] = []
        self.__environment_at_start = os.environ.copy()

        self.__is_shutdown = False
        self.__asyncio_loop: asyncio.AbstractEventLoop | None = None
        self.__logger = launch_logging.get_logger('launch.launch_context')

    # ---- the run -------------------------------------------------------------------------------------------

    @property
    def argv(self):
        """The arguments given to the launch service."""
        return self.__argv

    @property
    def noninteractive(self) -> bool:
        """True when the launch runs without a terminal (processes then get SIGINT from launch itself)."""
        return self.__noninteractive

    def _set_is_shutdown(self, state: bool) -> None:
        self.__is_shutdown = state

    @property
    def is_shutdown(self) -> bool:
        """True once the launch has begun shutting down."""
        return self.__is_shutdown

    def _set_asyncio_loop(self, loop: asyncio.AbstractEventLoop | None) -> None:
        self.__asyncio_loop = loop

    @property
    def asyncio_loop(self) -> asyncio.AbstractEventLoop | None:
        """The loop running the launch, None while it does not run."""
        return self.__asyncio_loop

    def add_completion_future(self, completion_future: asyncio.Future) -> None:
        """Make the launch wait for `completion_future` before it considers itself idle."""
        self._completion_futures.append(completion_future)

    # ---- locals --------------------------------------------------------------------------------------------

    def _push_locals(self) -> None:
        self.__locals_stack.append(dict(self.__locals))

    def _pop_locals(self) -> None:
        if not self.__locals_stack:
            raise RuntimeError('locals stack unexpectedly empty')
        self.__locals = self.__locals_stack.pop()
        self.__combined = None

    def extend_globals(self, extensions: dict[str, Any]) -> None:
        """Add variables seen in `locals` from now on, everywhere (a local of the same name hides one)."""
        self.__globals.update(extensions)
        self.__combined = None

    def extend_locals(self, extensions: dict[str, Any]) -> None:
        """Add variables to `locals` until the current scope is popped."""
        self.__locals.update(extensions)
        self.__combined = None

    def _clear_combined_locals_cache(self) -> None:
        self.__combined = None

    def get_locals_as_dict(self) -> dict[str, Any]:
        """Globals and locals (locals winning) as one dictionary."""
        if self.__combined is None:
            self.__combined = {**self.__globals, **self.__locals}
        return self.__combined

    @property
    def locals(self) -> Any:
        """Read-only attribute access to `get_locals_as_dict()`."""
        return _ReadOnlyLocals(self.get_locals_as_dict())

    # ---- environment ---------------------------------------------------------------------------------------

    def _push_environment(self) -> None:
        self.__environment_stack.append(os.environ.copy())

    def _pop_environment(self) -> None:
        if not self.__environment_stack:
            raise RuntimeError('environment stack unexpectedly empty')
        self.__replace_environment(self.__environment_stack.pop())

    def _reset_environment(self) -> None:
        self.__replace_environment(self.__environment_at_start)

    @staticmethod
    def __replace_environment(values: dict[str, str]) -> None:
        # os.environ must stay the os._Environ object (it writes through to the C environment)
        os.environ.clear()
        os.environ.update(values)

    @property
    def environment(self) -> MutableMapping[str, str]:
        """The environment processes inherit: this process's `os.environ`."""
        return os.environ

    # ---- launch configurations -----------------------------------------------------------------------------

    def _push_launch_configurations(self) -> None:
        self.__launch_configurations_stack.append(self.__launch_configurations.copy())

    def _pop_launch_configurations(self) -> None:
        if not self.__launch_configurations_stack:
            raise RuntimeError('launch_configurations stack unexpectedly empty')
        self.__launch_configurations = self.__launch_configurations_stack.pop()

    @property
    def launch_configurations(self) -> dict[str, str]:
        """Launch configurations (arguments, `let`s) by name."""
        return self.__launch_configurations

    # ---- events --------------------------------------------------------------------------------------------

    def would_handle_event(self, event: Event) -> bool:
        """True when some registered handler matches `event`."""
        return any(handler.matches(event) for handler in self._event_handlers)

    def register_event_handler(self, event_handler: BaseEventHandler, append: bool = False) -> None:
        """Register a handler: it is asked before the ones already there, or after them with `append`."""
        if append:
            self._event_handlers.append(event_handler)
        else:
            self._event_handlers.appendleft(event_handler)

    def unregister_event_handler(self, event_handler: BaseEventHandler) -> None:
        """Remove a registered handler (ValueError when it is not registered)."""
        self._event_handlers.remove(event_handler)

    def emit_event_sync(self, event: Event) -> None:
        """Queue `event` for the launch service, from the loop's thread, without awaiting."""
        self.__logger.debug(f"emitting event synchronously: '{event.name}'")
        self._event_queue.put_nowait(event)

    async def emit_event(self, event: Event) -> None:
        """Queue `event` for the launch service."""
        self.__logger.debug(f"emitting event: '{event.name}'")
        await self._event_queue.put(event)

    def perform_substitution(self, substitution: Substitution) -> str:
        """The text of `substitution` in this context."""
        return substitution.perform(self)
