"""Event handlers: run actions when a process starts or exits, or when the launch shuts down.

Python: `RegisterEventHandler(OnProcessExit(target_action=spawner, on_exit=[next_node]))`.
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

from typing import TYPE_CHECKING, Any

from diffctl.errors import LaunchError
from diffctl.launch.actions import Action
from diffctl.launch.plan import AddHandler, Handler, Step, TargetRef
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
    if callable(value) and not isinstance(value, (list, tuple)):
        raise LaunchError(f"{what}: callables are not supported, give a list of actions")
    items = list(value)
    for item in items:
        if not isinstance(item, Action):
            raise LaunchError(f"{what}: {item!r} is not a launch action")
    return items


class EventHandler:
    event = ""

    def __init__(self, target_action: Any = None, actions: Any = None, exit_code: int | None = None) -> None:
        self.targets = (
            []
            if target_action is None
            else (list(target_action) if isinstance(target_action, (list, tuple)) else [target_action])
        )
        self.actions = _actions(actions, type(self).__name__)
        if exit_code is not None and (isinstance(exit_code, bool) or not isinstance(exit_code, int)):
            raise LaunchError(f"exit_code {exit_code!r} must be an integer")
        self.exit_code = exit_code

    def resolve(self, r: Resolver, scope: Scope) -> Handler:
        refs = tuple(r.ref(t, scope) for t in self.targets)
        steps = r.visit_all(self.actions, scope.child())
        return Handler(self.event, refs, tuple(steps), self.exit_code)  # type: ignore[arg-type]


class OnProcessExit(EventHandler):
    event = "exit"

    def __init__(self, *, target_action: Any = None, on_exit: Any = None, exit_code: int | None = None) -> None:
        super().__init__(target_action, on_exit, exit_code)


class OnProcessStart(EventHandler):
    event = "start"

    def __init__(self, *, target_action: Any = None, on_start: Any = None) -> None:
        super().__init__(target_action, on_start)


class OnShutdown(EventHandler):
    event = "shutdown"

    def __init__(self, *, on_shutdown: Any = None) -> None:
        super().__init__(None, on_shutdown)


@register
class RegisterEventHandler(Action):
    yaml_tags = ("on_exit", "on_start", "on_shutdown")
    yaml_attrs = ("target", "exit_code", "do")

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
    def from_yaml(cls, e: Entity) -> Action:
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
