"""OpaqueCoroutine, ExecuteLocal and launch.descriptions.Executable, as ros2/launch (jazzy) defines them.

`OpaqueCoroutine(coroutine=f, args=…, kwargs=…, ignore_context=False)` runs `f(context, *args, **kwargs)` —
an `async def` — on the launch's thread. diffctl's loop is a selector loop, not asyncio's, so the coroutine
lives on a private asyncio loop that the launch pumps one iteration at a time from its own timers; the
launch stays up while the coroutine is pending (as ROS waits for an action's future) and cancels it on
shutdown (as ROS's OnShutdown handler does). `--print` cannot know what it will do and says so.

`ExecuteLocal(process_description=Executable(cmd=…, …), …)` is launch's base of ExecuteProcess: the process's
command, name, cwd and environment come from the description, the rest (output, respawn, …) from the action.
"""

from __future__ import annotations

import asyncio
import inspect
from collections.abc import Callable, Iterable, Mapping
from typing import TYPE_CHECKING, Any

from diffctl.errors import LaunchError
from diffctl.launch_legacy.actions import Action
from diffctl.launch_legacy.plan import Unknown
from diffctl.launch_legacy.process_actions import ExecuteProcess

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope

POLL_S = 0.01  # how often a coroutine waiting on something else than a timer is given a turn


def _asyncio_loop(engine: Any) -> asyncio.AbstractEventLoop:
    """One private asyncio loop per launch (never the running one: diffctl's loop is not asyncio's)."""
    loop = getattr(engine, "_asyncio_loop", None)
    if loop is None or loop.is_closed():
        loop = engine._asyncio_loop = asyncio.new_event_loop()
    return loop


def _close_when_idle(engine: Any, loop: asyncio.AbstractEventLoop) -> None:
    """The last coroutine is done: close its loop (a later OpaqueCoroutine makes a new one)."""
    if not loop.is_closed() and not asyncio.all_tasks(loop):
        loop.close()
        engine._asyncio_loop = None


def _next_turn_s(loop: asyncio.AbstractEventLoop) -> float:
    """When the coroutine can next make progress: now if callbacks are ready, at its earliest timer, or a poll."""
    if getattr(loop, "_ready", None):
        return 0.0
    scheduled = getattr(loop, "_scheduled", None)
    if scheduled:
        return min(POLL_S * 10, max(0.0, scheduled[0].when() - loop.time()))
    return POLL_S


class OpaqueCoroutine(Action):
    def __init__(
        self,
        *,
        coroutine: Callable[..., Any],
        args: Iterable[Any] | None = None,
        kwargs: Mapping[str, Any] | None = None,
        ignore_context: bool = False,
        **kw: Any,
    ) -> None:
        super().__init__(**kw)
        if not inspect.iscoroutinefunction(coroutine):
            raise LaunchError(
                f"OpaqueCoroutine needs a coroutine function (an `async def`), got {coroutine!r}",
                hint="for a plain function use OpaqueFunction",
            )
        self.coroutine = coroutine
        self.args = list(args or [])
        self.kwargs = dict(kwargs or {})
        self.ignore_context = ignore_context
        self.future: asyncio.Task[Any] | None = None

    def label(self) -> str:
        return f"OpaqueCoroutine {getattr(self.coroutine, '__name__', '?')}"

    def get_asyncio_future(self) -> asyncio.Task[Any] | None:
        return self.future

    def execute(self, context: Scope) -> list[Action] | None:
        engine = context.engine
        if engine.dry:
            engine.effect(Unknown(what=self.label(), why="a coroutine runs only when the launch runs"))
            return None
        args = self.args if self.ignore_context else [context, *self.args]
        loop = _asyncio_loop(engine)
        task = self.future = loop.create_task(self.coroutine(*args, **self.kwargs))
        what = self.label()

        def pump() -> None:
            loop.call_soon(loop.stop)
            loop.run_forever()  # one iteration: the coroutine runs until its next await
            if not task.done():
                engine.services.after(_next_turn_s(loop), pump, "timer")
            else:
                _close_when_idle(engine, loop)
                if not task.cancelled() and task.exception() is not None:
                    e = task.exception()
                    engine.failed(LaunchError(f"{what} raised {type(e).__name__}: {e}"))

        def cancel(_context: Any) -> None:
            if not task.done():
                task.cancel()
                loop.call_soon(loop.stop)
                loop.run_forever()  # let the coroutine see its CancelledError
                _close_when_idle(engine, loop)

        from diffctl.launch_legacy.event_actions import OpaqueFunction
        from diffctl.launch_legacy.event_handlers import OnShutdown

        context.register_event_handler(OnShutdown(on_shutdown=[OpaqueFunction(function=cancel)]))
        engine.defer(pump)
        return None


class Executable:
    """launch.descriptions.Executable: what to run (cmd, prefix, name, cwd, env, additional_env, arguments)."""

    def __init__(
        self,
        *,
        cmd: Iterable[Any],
        prefix: Any = None,
        name: Any = None,
        cwd: Any = None,
        env: Mapping[str, Any] | None = None,
        additional_env: Mapping[str, Any] | None = None,
        arguments: Iterable[Any] | None = None,
    ) -> None:
        self.cmd = list(cmd)
        self.prefix = prefix
        self.name = name
        self.cwd = cwd
        self.env = env
        self.additional_env = additional_env
        self.arguments = list(arguments or [])


class ExecuteLocal(ExecuteProcess):
    """launch.actions.ExecuteLocal: an ExecuteProcess whose command comes from an `Executable`."""

    frontend_tags = ()

    def __init__(self, *, process_description: Executable, **kw: Any) -> None:
        if not isinstance(process_description, Executable):
            raise LaunchError(
                f"ExecuteLocal: process_description must be a launch.descriptions.Executable, got "
                f"{process_description!r}"
            )
        d = self.process_description = process_description
        super().__init__(
            cmd=[*d.cmd, *d.arguments],
            name=d.name,
            cwd=d.cwd,
            env=d.env,
            additional_env=d.additional_env,
            prefix=d.prefix,
            **kw,
        )
