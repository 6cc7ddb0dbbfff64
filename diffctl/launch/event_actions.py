"""EmitEvent and OpaqueFunction: the Python-only actions that run user code or emit events.

`EmitEvent(event=Shutdown(...))` shuts the launch down; `EmitEvent(event=SignalProcess(signal_number=…,
process_matcher=matches_action(node)))` signals a process's group; `ShutdownProcess` stops it as shutdown
would. `OpaqueFunction(function=f, args=…, kwargs=…)` calls `f(context, *args, **kwargs)` while the
description is resolved; `context.launch_configurations` and `Substitution.perform(context)` work as in ROS,
and the actions it returns are resolved in its place.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from typing import TYPE_CHECKING, Any

from diffctl.errors import DiffctlError, LaunchError
from diffctl.launch.actions import Action, Shutdown
from diffctl.launch.events import Shutdown as ShutdownEvent
from diffctl.launch.events import ShutdownProcess, SignalProcess
from diffctl.launch.plan import RequestShutdown, SignalProcesses, Step, TargetRef
from diffctl.launch.substitutions import perform

if TYPE_CHECKING:
    from diffctl.launch.context import Scope
    from diffctl.launch.resolver import Resolver


class EmitEvent(Action):
    """Emit an event: Shutdown, SignalProcess or ShutdownProcess."""

    def __init__(self, *, event: Any, **kw: Any) -> None:
        super().__init__(**kw)
        if not isinstance(event, (ShutdownEvent, Shutdown, SignalProcess, ShutdownProcess)):
            raise LaunchError(
                f"EmitEvent: {type(event).__name__} events are not supported",
                hint="valid: events.Shutdown, events.process.SignalProcess, events.process.ShutdownProcess",
            )
        self.event = event

    def label(self) -> str:
        return f"emit {type(self.event).__name__}"

    def visit(self, r: Resolver, scope: Scope) -> list[Step]:
        if isinstance(self.event, Shutdown):
            return self.event.visit(r, scope)
        if isinstance(self.event, ShutdownEvent):
            return [RequestShutdown(reason=perform(self.event.reason, scope))]
        m = self.event.matcher
        ref = r.ref(m.action, scope) if m.action is not None else TargetRef(name=m.name, label=m.name or "")
        sig = int(self.event.signal) if isinstance(self.event, SignalProcess) else None
        return [SignalProcesses(signal=sig, targets=(ref,))]


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
        code = getattr(function, "__code__", None)
        where = f" ({code.co_filename}:{code.co_firstlineno})" if code is not None else ""
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

    def visit(self, r: Resolver, scope: Scope) -> list[Step]:
        what = f"OpaqueFunction {getattr(self.function, '__name__', '?')}"
        result = call_user(self.function, what, scope, *self.args, **self.kwargs)
        return r.visit_all(returned_actions(result, what), scope)
