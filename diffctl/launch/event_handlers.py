"""Event handlers: run actions when a process starts or exits, or when the launch shuts down.

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
from diffctl.launch import events
from diffctl.launch.actions import Action
from diffctl.launch.event_actions import call_user, returned_actions
from diffctl.launch.plan import AddHandler, EventInfo, Handler, Step, TargetRef
from diffctl.launch.registry import register
from diffctl.launch.substitutions import normalize, perform

if TYPE_CHECKING:
    from diffctl.launch.context import Scope
    from diffctl.launch.resolver import Resolver
    from diffctl.launch.yaml_frontend import Entity


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


class EventHandler:
    """Actions to run on an event, or a callable `(event, context)` returning actions (resolved when it fires)."""

    event = ""

    def __init__(
        self, target_action: Any = None, actions: Any = None, exit_code: int | None = None, handle_once: bool = False
    ) -> None:
        self.targets = (
            []
            if target_action is None
            else (list(target_action) if isinstance(target_action, (list, tuple)) else [target_action])
        )
        self.callback: Callable[..., Any] | None = None
        if callable(actions) and not isinstance(actions, Action):
            self.callback, actions = actions, None
        self.actions = _actions(actions, type(self).__name__)
        if exit_code is not None and (isinstance(exit_code, bool) or not isinstance(exit_code, int)):
            raise LaunchError(f"exit_code {exit_code!r} must be an integer")
        self.exit_code = exit_code
        self.handle_once = handle_once

    def make_event(self, info: EventInfo, r: Resolver, scope: Scope) -> Any:
        action = r.process_actions.get(info.name)
        spec = r.processes.get(info.name)
        common = {
            "action": action,
            "name": info.name,
            "pid": info.pid,
            "cmd": list(spec.argv) if spec else [],
            "cwd": spec.cwd if spec else None,
            "env": dict(scope.env),
        }
        if self.event == "exit":
            return events.ProcessExited(**common, returncode=info.exit_code or 0)
        if self.event == "start":
            return events.ProcessStarted(**common)
        return events.Shutdown(reason=info.text or "")

    def call(self, info: EventInfo, r: Resolver, scope: Scope) -> tuple[Step, ...]:
        assert self.callback is not None
        what = f"{type(self).__name__} callable {getattr(self.callback, '__name__', '')}".rstrip()
        result = call_user(self.callback, what, self.make_event(info, r, scope), scope)
        return tuple(r.resolve_more(returned_actions(result, what), scope.child()))

    def resolve(self, r: Resolver, scope: Scope) -> Handler:
        refs = tuple(r.ref(t, scope) for t in self.targets)
        steps = r.visit_all(self.actions, scope.child())
        callback = None
        if self.callback is not None:
            inner = scope.child()
            callback = lambda info: self.call(info, r, inner)  # noqa: E731
        return Handler(
            self.event,  # type: ignore[arg-type]
            refs,
            tuple(steps),
            self.exit_code,
            callback=callback,
            describe_callback=getattr(self.callback, "__name__", "") if self.callback else "",
            once=self.handle_once,
        )


class OnProcessExit(EventHandler):
    event = "exit"

    def __init__(
        self, *, target_action: Any = None, on_exit: Any = None, exit_code: int | None = None, handle_once: bool = False
    ) -> None:
        super().__init__(target_action, on_exit, exit_code, handle_once)


class OnProcessStart(EventHandler):
    event = "start"

    def __init__(self, *, target_action: Any = None, on_start: Any = None, handle_once: bool = False) -> None:
        super().__init__(target_action, on_start, None, handle_once)


class OnShutdown(EventHandler):
    event = "shutdown"

    def __init__(self, *, on_shutdown: Any = None, handle_once: bool = False) -> None:
        super().__init__(None, on_shutdown, None, handle_once)


class OnProcessIO(EventHandler):
    """Callables on a process's output lines: `on_stdout(event)` / `on_stderr(event)`, `event.text` as bytes."""

    event = "io"

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

    def call_io(self, info: EventInfo, r: Resolver, scope: Scope) -> tuple[Step, ...]:
        fn = self.on_stdout if info.stream == "stdout" else self.on_stderr
        assert fn is not None
        what = f"OnProcessIO {info.stream} callable {getattr(fn, '__name__', '')}".rstrip()
        spec = r.processes.get(info.name)
        event = events.ProcessIO(
            action=r.process_actions.get(info.name),
            name=info.name,
            pid=info.pid,
            cmd=list(spec.argv) if spec else [],
            text=((info.text or "") + "\n").encode(),
            fd=1 if info.stream == "stdout" else 2,
        )
        result = call_user(fn, what, event)
        return tuple(r.resolve_more(returned_actions(result, what), scope.child()))

    def resolve(self, r: Resolver, scope: Scope) -> Handler:
        refs = tuple(r.ref(t, scope) for t in self.targets)
        streams = tuple(s for s, fn in (("stdout", self.on_stdout), ("stderr", self.on_stderr)) if fn is not None)
        inner = scope.child()
        return Handler(
            "io",
            refs,
            (),
            callback=lambda info: self.call_io(info, r, inner),
            streams=streams,
            describe_callback=", ".join(
                getattr(fn, "__name__", "?") for fn in (self.on_stdout, self.on_stderr) if fn is not None
            ),
            once=self.handle_once,
        )


@register
class RegisterEventHandler(Action):
    frontend_tags = ("on_exit", "on_start", "on_shutdown")
    frontend_attrs = ("target", "exit_code", "do")

    def __init__(self, event_handler: EventHandler, **kw: Any) -> None:
        super().__init__(**kw)
        if not isinstance(event_handler, EventHandler):
            raise LaunchError(
                f"RegisterEventHandler needs an event handler, got {event_handler!r}",
                hint="valid: OnProcessExit, OnProcessStart, OnShutdown",
            )
        self.event_handler = event_handler

    def label(self) -> str:
        return f"on_{self.event_handler.event}"

    def visit(self, r: Resolver, scope: Scope) -> list[Step]:
        return [AddHandler(handler=self.event_handler.resolve(r, scope))]

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


class YamlTarget:
    """A process named by text in YAML (possibly with substitutions)."""

    def __init__(self, text: Any) -> None:
        self.text = text

    def ref(self, scope: Scope) -> TargetRef:
        name = perform(self.text, scope)
        return TargetRef(name=name, label=name)
