"""Event handlers, as ros2/launch's: registered in the context (newest first), each offered every event.

A handler matches an event (its type, its target process, for OnProcessExit optionally its exit code) and
returns the entities to visit then: its actions, or what its callable `(event, context)` returns when called
at event time (OnProcessIO's callables get the event only, as in ROS).

Python: `RegisterEventHandler(OnProcessExit(target_action=spawner, on_exit=[next_node]))`, or a callable
`on_exit=lambda event, context: [...]` called when the event happens; `OnProcessIO(on_stdout=lambda event: …)`.
YAML (which ros2 launch lacks):

    - on_exit:
        target: base_spawner     # process name(s); omit for any process
        exit_code: 0             # optional: only on this exit code
        do:
          - node: {pkg: controller_manager, exec: spawner, args: joint_state_broadcaster}
    - on_start: {target: sim, do: [...]}
    - on_shutdown: {do: [{log: {message: bye}}]}
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from diffctl.errors import LaunchError
from diffctl.launch_legacy import events
from diffctl.launch_legacy.actions import Action
from diffctl.launch_legacy.event_actions import call_user, returned_actions
from diffctl.launch_legacy.registry import register
from diffctl.launch_legacy.substitutions import Substitution, normalize, perform

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope
    from diffctl.launch_legacy.yaml_frontend import Entity


def _actions(value: Any, what: str) -> list[Action]:
    if value is None:
        return []
    if isinstance(value, Action):
        return [value]
    items = list(value)
    for item in items:
        if not isinstance(item, Action):
            raise LaunchError(f"{what}: {item!r} is not a launch action")
    return items


class YamlTarget:
    """A process named by text in YAML (possibly with substitutions), resolved when the handler is registered."""

    def __init__(self, text: Any) -> None:
        self.text = text


class BaseEventHandler:
    """A handler: `matches(event)` and `handle(event, context)` → entities (launch.EventHandler)."""

    kind = ""
    event_type: type | tuple[type, ...] = events.Event

    def __init__(
        self, *, matcher: Callable[[Any], bool] | None = None, entities: Any = None, handle_once: bool = False
    ) -> None:
        self.matcher = matcher
        self.entities = _actions(entities, type(self).__name__)
        self.callable: Callable[..., Any] | None = None
        self.handle_once = handle_once
        self.exit_code: int | None = None
        self.streams: tuple[str, ...] = ()
        self.launch_file: str | None = None
        self.seq = 0

    def matches(self, event: Any) -> bool:
        if self.matcher is not None:
            return bool(self.matcher(event))
        return isinstance(event, self.event_type)

    def handle(self, event: Any, context: Scope) -> list[Action] | None:
        context.extend_locals({"event": event})
        if self.handle_once:
            context.unregister_event_handler(self)
        if self.callable is not None:
            what = f"{type(self).__name__} callable {getattr(self.callable, '__name__', '')}".rstrip()
            return returned_actions(self.call(event, context), what)
        return list(self.entities)

    def call(self, event: Any, context: Scope) -> Any:
        assert self.callable is not None
        what = f"{type(self).__name__} callable {getattr(self.callable, '__name__', '')}".rstrip()
        return call_user(self.callable, what, event, context)

    def name_targets(self) -> list[Any]:
        return []

    def describe_callable(self) -> str:
        return getattr(self.callable, "__name__", "a function") if self.callable is not None else ""

    def resolve_names(self, context: Scope) -> None:
        """Process names written as text are substituted when the handler is registered."""


EventHandler = BaseEventHandler


class OnActionEventBase(BaseEventHandler):
    """A handler of one action's events: `target_action` an action, a process name, a predicate, or None (any)."""

    def __init__(
        self, target_action: Any = None, actions: Any = None, exit_code: int | None = None, handle_once: bool = False
    ) -> None:
        fn = actions if callable(actions) and not isinstance(actions, Action) else None
        super().__init__(entities=None if fn is not None else actions, handle_once=handle_once)
        self.callable = fn
        if target_action is None:
            self.targets: list[Any] = []
        elif isinstance(target_action, (list, tuple)):
            self.targets = list(target_action)
        else:
            self.targets = [target_action]
        if exit_code is not None and (isinstance(exit_code, bool) or not isinstance(exit_code, int)):
            raise LaunchError(f"exit_code {exit_code!r} must be an integer")
        self.exit_code = exit_code
        self._names: set[str] = set()

    def resolve_names(self, context: Scope) -> None:
        for t in self.targets:
            if isinstance(t, YamlTarget):
                self._names.add(perform(t.text, context))
            elif isinstance(t, (str, Substitution, list, tuple)):
                self._names.add(perform(t, context))

    def name_targets(self) -> list[Any]:
        out: list[Any] = []
        for t in self.targets:
            if isinstance(t, Action):
                out.append(t)
            elif isinstance(t, YamlTarget):
                out.append(t.text)
            elif isinstance(t, (str, Substitution)):
                out.append(t)
        return out

    def target_matches(self, action: Any, name: str | None) -> bool:
        if not self.targets:
            return True
        for t in self.targets:
            if isinstance(t, Action):
                if t is action:
                    return True
            elif callable(t) and not isinstance(t, (str, Substitution, YamlTarget)) and t(action):
                return True
        return name is not None and name in self._names

    def matches(self, event: Any) -> bool:
        if not isinstance(event, self.event_type):
            return False
        return self.target_matches(getattr(event, "action", None), getattr(event, "name", None))


class OnProcessExit(OnActionEventBase):
    kind = "exit"
    event_type = events.ProcessExited

    def __init__(
        self, *, target_action: Any = None, on_exit: Any = None, exit_code: int | None = None, handle_once: bool = False
    ) -> None:
        super().__init__(target_action, on_exit, exit_code, handle_once)

    def matches(self, event: Any) -> bool:
        return super().matches(event) and (self.exit_code is None or event.returncode == self.exit_code)


class OnProcessStart(OnActionEventBase):
    kind = "start"
    event_type = events.ProcessStarted

    def __init__(self, *, target_action: Any = None, on_start: Any = None, handle_once: bool = False) -> None:
        super().__init__(target_action, on_start, None, handle_once)


class OnExecutionComplete(OnActionEventBase):
    kind = "complete"
    event_type = events.ExecutionComplete

    def __init__(self, *, target_action: Any = None, on_completion: Any = None, handle_once: bool = False) -> None:
        super().__init__(target_action, on_completion, None, handle_once)

    def matches(self, event: Any) -> bool:
        if not isinstance(event, events.ExecutionComplete):
            return False
        if not self.targets:
            return True
        return self.target_matches(event.action, None) or (
            event.action is not None and getattr(event.action, "_process_name", None) in self._names
        )


class OnShutdown(BaseEventHandler):
    kind = "shutdown"
    event_type = events.Shutdown

    def __init__(self, *, on_shutdown: Any = None, handle_once: bool = False) -> None:
        fn = on_shutdown if callable(on_shutdown) and not isinstance(on_shutdown, Action) else None
        super().__init__(entities=None if fn is not None else on_shutdown, handle_once=handle_once)
        self.callable = fn


class OnProcessIO(OnActionEventBase):
    """Callables on a process's output: `on_stdout(event)` / `on_stderr(event)`, `event.text` as bytes."""

    kind = "io"
    event_type = events.ProcessIO

    def __init__(
        self,
        *,
        target_action: Any = None,
        on_stdin: Any = None,
        on_stdout: Callable[..., Any] | None = None,
        on_stderr: Callable[..., Any] | None = None,
        handle_once: bool = False,
    ) -> None:
        super().__init__(target_action, None, None, handle_once)
        if on_stdin is not None:
            raise LaunchError("OnProcessIO(on_stdin=…) is not supported: launched processes read no stdin")
        for what, fn in (("on_stdout", on_stdout), ("on_stderr", on_stderr)):
            if fn is not None and not callable(fn):
                raise LaunchError(f"OnProcessIO {what} must be a callable taking the event")
        self.on_stdout, self.on_stderr = on_stdout, on_stderr
        self.streams = tuple(s for s, fn in (("stdout", on_stdout), ("stderr", on_stderr)) if fn is not None)
        self.callable = on_stdout or on_stderr

    def matches(self, event: Any) -> bool:
        if not super().matches(event):
            return False
        return (self.on_stdout if event.fd == 1 else self.on_stderr if event.fd == 2 else None) is not None

    def call(self, event: Any, context: Scope) -> Any:
        fn = self.on_stdout if event.fd == 1 else self.on_stderr
        assert fn is not None
        stream = "stdout" if event.fd == 1 else "stderr"
        return call_user(fn, f"OnProcessIO {stream} callable {getattr(fn, '__name__', '')}".rstrip(), event)

    def describe_callable(self) -> str:
        return ", ".join(getattr(fn, "__name__", "?") for fn in (self.on_stdout, self.on_stderr) if fn is not None)


@register
class RegisterEventHandler(Action):
    frontend_tags = ("on_exit", "on_start", "on_shutdown")
    frontend_attrs = ("target", "exit_code", "do")

    def __init__(self, event_handler: EventHandler, **kw: Any) -> None:
        super().__init__(**kw)
        if not isinstance(event_handler, BaseEventHandler):
            raise LaunchError(
                f"RegisterEventHandler needs an event handler, got {event_handler!r}",
                hint="valid: OnProcessExit, OnProcessStart, OnShutdown",
            )
        self.event_handler = event_handler

    def label(self) -> str:
        return f"on_{self.event_handler.kind}"

    def execute(self, context: Scope) -> list[Action] | None:
        self.event_handler.resolve_names(context)
        context.register_event_handler(self.event_handler)
        return None

    def describe_sub_entities(self) -> list[Action]:
        return list(self.event_handler.entities)

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        if e.tag == "on_shutdown" and e.has("target"):
            raise e.error("on_shutdown takes no target", key="target")
        if e.tag != "on_exit" and e.has("exit_code"):
            raise e.error("only on_exit takes exit_code", key="exit_code")
        raw = e.raw("target")
        names = raw if isinstance(raw, list) else ([] if raw is None else [raw])
        targets = [YamlTarget(normalize(e.parse(str(n)))) for n in names]
        actions = e.children("do")
        if e.tag == "on_exit":
            code = e.raw("exit_code")
            if code is not None and (isinstance(code, bool) or not isinstance(code, int)):
                raise e.error(f"exit_code {code!r} must be an integer", key="exit_code")
            return cls(OnProcessExit(target_action=targets or None, on_exit=actions, exit_code=code))
        if e.tag == "on_start":
            return cls(OnProcessStart(target_action=targets or None, on_start=actions))
        return cls(OnShutdown(on_shutdown=actions))


class UnregisterEventHandler(Action):
    def __init__(self, event_handler: BaseEventHandler, **kw: Any) -> None:
        super().__init__(**kw)
        self.event_handler = event_handler

    def execute(self, context: Scope) -> list[Action] | None:
        if not context.engine.dry:
            context.unregister_event_handler(self.event_handler)
        return None
