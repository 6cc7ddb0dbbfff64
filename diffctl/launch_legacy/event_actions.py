"""EmitEvent and OpaqueFunction: the Python-only actions that run user code or emit events.

`EmitEvent(event=Shutdown(...))` shuts the launch down; `EmitEvent(event=SignalProcess(signal_number=…,
process_matcher=matches_action(node)))` signals a process's group; `ShutdownProcess` stops it as shutdown
would. `OpaqueFunction(function=f, args=…, kwargs=…)` calls `f(context, *args, **kwargs)` while the
engine reaches it; `context.launch_configurations` and `Substitution.perform(context)` work as in ROS,
and the actions it returns are resolved in its place.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from typing import TYPE_CHECKING, Any

from diffctl.errors import DiffctlError, LaunchError
from diffctl.launch_legacy.actions import Action, Shutdown
from diffctl.launch_legacy.events import IncludeLaunchDescription as IncludeEvent
from diffctl.launch_legacy.events import Shutdown as ShutdownEvent
from diffctl.launch_legacy.events import ShutdownProcess, SignalProcess
from diffctl.launch_legacy.plan import RequestShutdown, SignalProcesses, TargetRef
from diffctl.launch_legacy.substitutions import perform

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope


class EmitEvent(Action):
    """Emit an event: Shutdown, SignalProcess or ShutdownProcess."""

    def __init__(self, *, event: Any, **kw: Any) -> None:
        super().__init__(**kw)
        from diffctl.launch_legacy.events import Event

        if not isinstance(event, (ShutdownEvent, Shutdown, SignalProcess, ShutdownProcess, Event)):
            raise LaunchError(
                f"EmitEvent: {event!r} is not a launch event",
                hint="valid: events.Shutdown, events.process.SignalProcess, events.process.ShutdownProcess, …",
            )
        self.event = event

    def label(self) -> str:
        return f"emit {type(self.event).__name__}"

    def execute(self, context: Scope) -> list[Action] | None:
        engine = context.engine
        if isinstance(self.event, Shutdown):
            return self.event.execute(context)
        if isinstance(self.event, ShutdownEvent):
            engine.effect(RequestShutdown(reason=perform(self.event.reason, context)))
            return None
        if not isinstance(self.event, (SignalProcess, ShutdownProcess)):
            if engine.dry:
                if isinstance(self.event, IncludeEvent):  # --print: what it includes, shown in its place
                    return [self.event.launch_description]
                return None
            engine.emit(self.event)  # queued: handled after the current event, as EmitEvent does
            return None
        m = self.event.matcher
        ref = engine.ref(m.action) if m.action is not None else TargetRef(name=m.name, label=m.name or "")
        sig = int(self.event.signal) if isinstance(self.event, SignalProcess) else None
        engine.effect(SignalProcesses(signal=sig, targets=(ref,)))
        return None


def returned_actions(result: Any, what: str) -> list[Action]:
    """What a user function returned: None, an action, or a list of actions (anything else is an error)."""
    if result is None:
        return []
    if isinstance(result, Action):
        return [result]
    if isinstance(result, Iterable) and not isinstance(result, (str, bytes, Mapping)):
        items = list(result)
        for item in items:
            if not isinstance(item, Action):
                raise LaunchError(f"{what} returned {item!r}, which is not a launch action")
        return items
    raise LaunchError(f"{what} returned {result!r}; it must return launch actions or None")


def call_user(function: Callable[..., Any], what: str, *args: Any, **kwargs: Any) -> Any:
    """Call launch-file code; its exceptions become one LaunchError naming the function."""
    try:
        return function(*args, **kwargs)
    except DiffctlError:
        raise
    except Exception as e:
        from diffctl.source_paths import user_source

        code = getattr(function, "__code__", None)
        where = f" ({user_source(code.co_filename)}:{code.co_firstlineno})" if code is not None else ""
        raise LaunchError(f"{what}{where} raised {type(e).__name__}: {e}") from None


class OpaqueFunction(Action):
    def __init__(
        self,
        *,
        function: Callable[..., Any],
        args: Iterable[Any] | None = None,
        kwargs: Mapping[str, Any] | None = None,
        **kw: Any,
    ) -> None:
        super().__init__(**kw)
        if not callable(function):
            raise LaunchError(f"OpaqueFunction needs a callable, got {function!r}")
        self.function = function
        self.args = list(args or [])
        self.kwargs = dict(kwargs or {})

    def label(self) -> str:
        return f"OpaqueFunction {getattr(self.function, '__name__', '?')}"

    def execute(self, context: Scope) -> list[Action] | None:
        what = f"OpaqueFunction {getattr(self.function, '__name__', '?')}"
        result = call_user(self.function, what, context, *self.args, **self.kwargs)
        return returned_actions(result, what)
