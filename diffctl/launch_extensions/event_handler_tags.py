"""`on_exit`, `on_start` and `on_shutdown` as YAML and XML tags (ros2 launch's frontends have Python's
RegisterEventHandler only):

    - on_exit:
        target: spawner_diffbot_base_controller   # a process name, or a list of them; none: any process
        exit_code: 0                              # on_exit only: just this exit code
        do: [{node: {pkg: controller_manager, exec: spawner, args: joint_state_broadcaster}}]
    - on_start: {target: sim, do: [{log: {message: "sim is up"}}]}
    - on_shutdown: {do: [{log: {message: bye}}]}

    <on_exit target="a" exit_code="0"><log message="a done"/></on_exit>

A process is named as in the launch file: a Node by its node name, anything by its `name` (or executable),
with or without the `-N` ros2 launch appends. Names are substituted when the handler is registered.
"""

from __future__ import annotations

from typing import Any

from diffctl.errors import LaunchError
from diffctl.launch.actions import RegisterEventHandler
from diffctl.launch.event_handlers import OnProcessExit, OnProcessStart, OnShutdown
from diffctl.launch.frontend import Entity, Parser, expose_action
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.utilities import perform_substitutions
from diffctl.launch_extensions import frontend_values
from diffctl.launch_extensions.process_watch import process_names


class ProcessNamed:
    """An action matcher: the process actions called by one of these names (substituted at registration)."""

    def __init__(self, names: list[Any]) -> None:
        self.names = names
        self.resolved: set[str] | None = None

    def resolve(self, context: LaunchContext) -> None:
        self.resolved = {perform_substitutions(context, n) for n in self.names}

    def __call__(self, action: Any) -> bool:
        return self.resolved is not None and not self.resolved.isdisjoint(process_names(action))

    def __repr__(self) -> str:
        return "process named " + " or ".join(
            "".join(getattr(s, "text", None) or s.describe() for s in n) for n in self.names
        )


class OnProcessExitWithCode(OnProcessExit):
    """OnProcessExit of one exit code only."""

    def __init__(self, *, exit_code: int, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.exit_code = exit_code

    def matches(self, event: Any) -> bool:
        return super().matches(event) and event.returncode == self.exit_code

    @property
    def matcher_description(self) -> str:
        return f"{super().matcher_description} and event.returncode == {self.exit_code}"


class RegisterNamedEventHandler(RegisterEventHandler):
    """RegisterEventHandler whose handler names its processes by text: the names are substituted now."""

    def __init__(self, event_handler: Any, *, process_matcher: ProcessNamed | None = None, **kwargs: Any) -> None:
        super().__init__(event_handler, **kwargs)
        self.process_matcher = process_matcher

    def execute(self, context: LaunchContext) -> Any:
        if self.process_matcher is not None:
            self.process_matcher.resolve(context)
        return super().execute(context)


def _parse(entity: Entity, parser: Parser, kind: str) -> tuple[type, dict[str, Any]]:
    _, kwargs = RegisterEventHandler.parse(entity, parser)  # if / unless
    kwargs.pop("event_handler", None)
    targets = None if kind == "shutdown" else entity.get_attr("target", data_type=None, optional=True)
    if kind == "shutdown" and entity.get_attr("target", data_type=None, optional=True) is not None:
        raise LaunchError("on_shutdown takes no target", field="on_shutdown.target")
    exit_code = None
    if kind == "exit":
        exit_code = entity.get_attr("exit_code", data_type=int, optional=True, can_be_str=False)
        if isinstance(exit_code, bool):
            raise LaunchError(f"exit_code {exit_code!r} must be an integer", field="on_exit.exit_code")
    items = frontend_values.action_entities(entity, "do")
    if not items:
        raise LaunchError(f"on_{kind} needs the actions to run: `do: [...]`", field=f"on_{kind}.do")
    actions = [parser.parse_action(child) for child in items]
    names = [targets] if isinstance(targets, (str, int, float)) else (targets or [])
    matcher = ProcessNamed([parser.parse_substitution(str(n)) for n in names]) if names else None
    handler: Any
    if kind == "exit":
        common = {"target_action": matcher, "on_exit": actions}
        handler = OnProcessExit(**common) if exit_code is None else OnProcessExitWithCode(exit_code=exit_code, **common)
    elif kind == "start":
        handler = OnProcessStart(target_action=matcher, on_start=actions)
    else:
        handler = OnShutdown(on_shutdown=actions)
    kwargs.update(event_handler=handler, process_matcher=matcher)
    return RegisterNamedEventHandler, kwargs


@expose_action("on_exit")
def parse_on_exit(entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
    """`on_exit`: RegisterEventHandler(OnProcessExit(...)), optionally of one exit code."""
    return _parse(entity, parser, "exit")


@expose_action("on_start")
def parse_on_start(entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
    """`on_start`: RegisterEventHandler(OnProcessStart(...))."""
    return _parse(entity, parser, "start")


@expose_action("on_shutdown")
def parse_on_shutdown(entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
    """`on_shutdown`: RegisterEventHandler(OnShutdown(...))."""
    return _parse(entity, parser, "shutdown")
