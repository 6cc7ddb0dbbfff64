"""The description model: launch actions named as in `launch` (DeclareLaunchArgument, GroupAction, …).

Every frontend builds these objects: Python launch files construct them, the YAML and XML frontends build
them with each class's `from_entity` (the entity's accessors hide which of the two it came from).
`execute(context)` does what the action does when the engine reaches it (engine.py) and returns the entities
to visit next, as ros2/launch's `Action.execute`.
Processes (ExecuteProcess, Node) live in process_actions.py, event handlers in event_handlers.py, includes in
include_action.py, EmitEvent and OpaqueFunction in event_actions.py, launch_ros's scope actions in ros_actions.py.
"""

from __future__ import annotations

import os
import sys
from abc import ABC, abstractmethod
from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING, Any, ClassVar

from diffctl.errors import LaunchError
from diffctl.launch_legacy.conditions import Condition
from diffctl.launch_legacy.plan import Argument, LogMessage, RequestShutdown, StartTimer, Unknown, Where
from diffctl.launch_legacy.readiness import WaitFor, parse_timeout, parse_wait_for
from diffctl.launch_legacy.registry import register
from diffctl.launch_legacy.substitutions import FileContent, SomeSubstitutions, Substitution, normalize, perform

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope
    from diffctl.launch_legacy.yaml_frontend import Entity

_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))


def caller_where() -> Where:
    """The first stack frame outside diffctl.launch_legacy: where a Python launch file built this action."""
    frame = sys._getframe(1)
    while frame is not None and os.path.dirname(os.path.abspath(frame.f_code.co_filename)) == _PACKAGE_DIR:
        frame = frame.f_back
    if frame is None:
        return Where()
    return Where(frame.f_code.co_filename, frame.f_lineno)


def describe(value: Any) -> str:
    """Substitutions as written (`$(var x)`), for labels of entities that were not resolved."""
    if value is None:
        return ""
    return "".join(s.describe() for s in normalize(value))


class Action(ABC):
    """Base of everything a launch description holds. Every action takes `condition`, `wait_for`, `wait_timeout`."""

    frontend_tags: ClassVar[tuple[str, ...]] = ()
    frontend_attrs: ClassVar[tuple[str, ...]] = ()

    def __init__(
        self,
        *,
        condition: Condition | None = None,
        wait_for: Iterable[WaitFor | Mapping[str, Any]] | None = None,
        wait_timeout: float | None = None,
    ) -> None:
        self.condition = condition
        self.wait_for: list[WaitFor] = parse_wait_for(list(wait_for) if wait_for is not None else None)
        self.wait_timeout = parse_timeout(wait_timeout)
        self.where = caller_where()

    def label(self) -> str:
        return self.frontend_tags[0] if self.frontend_tags else type(self).__name__

    @abstractmethod
    def execute(self, context: Scope) -> list[Action] | None:
        """Do what the action does, now; return the entities to visit next."""

    def describe_sub_entities(self) -> list[Action]:
        return []

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        raise LaunchError(f"`{e.tag}` cannot be written in YAML or XML launch files", hint="use the Python frontend")


class LaunchDescription(Action):
    """The list of entities a launch file returns; may itself be an entity of another description."""

    def __init__(self, initial_entities: Iterable[Action] | None = None, **kw: Any) -> None:
        super().__init__(**kw)
        self.entities: list[Action] = []
        for entity in initial_entities or []:
            self.add_action(entity)

    def add_action(self, action: Action) -> None:
        if not isinstance(action, Action):
            raise LaunchError(f"LaunchDescription entries must be launch actions, got {action!r}")
        self.entities.append(action)

    add_entity = add_action

    def execute(self, context: Scope) -> list[Action] | None:
        return list(self.entities)

    def describe_sub_entities(self) -> list[Action]:
        return list(self.entities)


@register
class DeclareLaunchArgument(Action):
    frontend_tags = ("arg",)
    frontend_attrs = ("name", "default", "description", "choice", "choices")

    def __init__(
        self,
        name: str,
        *,
        default_value: SomeSubstitutions | None = None,
        description: str = "",
        choices: Iterable[str] | None = None,
        **kw: Any,
    ) -> None:
        super().__init__(**kw)
        if not isinstance(name, str) or not name:
            raise LaunchError(f"a launch argument needs a name, got {name!r}")
        self.name = name
        self.default_value = None if default_value is None else normalize(default_value)
        self.description = description
        self.choices = tuple(str(c) for c in choices) if choices is not None else None

    def label(self) -> str:
        return f"arg {self.name}"

    def execute(self, context: Scope) -> list[Action] | None:
        scope = context
        default = None if self.default_value is None else perform(self.default_value, scope)
        if self.name in scope.configurations:  # from anywhere: the command line, an include, a `let` (as ROS)
            value: str | None = scope.configurations[self.name]
        elif default is not None:
            value = default
            scope.configurations[self.name] = value
        else:
            value = scope.engine.missing_argument(self.name)
        if self.choices is not None and value is not None and value not in self.choices:
            raise LaunchError(
                f"argument {self.name!r} is {value!r}, not one of its choices",
                hint="valid: " + ", ".join(self.choices),
            )
        scope.engine.declare(Argument(self.name, value, default, self.description, self.choices, str(self.where)))
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        # launch_yaml's form is `choice: [{value: a}, {value: b}]` (launch_xml's `<choice value=…/>`);
        # diffctl's earlier `choices: [a, b]` stays as an alias.
        if e.has("choice") and e.has("choices"):
            raise e.error("give `choice` or `choices`, not both", key="choices")
        choices: list[str] | None = None
        if e.has("choice"):
            choices = [c.plain("value", required=True) for c in e.items("choice", ("value",))]
        elif e.raw("choices") is not None:
            raw = e.raw("choices")
            if not isinstance(raw, list):
                raise e.error("choices must be a list", key="choices")
            choices = [str(c) for c in raw]
        if choices is not None and not choices:
            raise e.error("an argument's choices cannot be empty", key="choice")
        return cls(
            e.plain("name", required=True),
            default_value=e.text("default"),
            description=e.plain("description") or "",
            choices=choices,
        )


@register
class SetLaunchConfiguration(Action):
    """`let`: set a launch configuration; `let: {name, file, replace}` reads a file with placeholders replaced."""

    frontend_tags = ("let",)
    frontend_attrs = ("name", "value", "file", "replace")

    def __init__(self, name: SomeSubstitutions, value: SomeSubstitutions, **kw: Any) -> None:
        super().__init__(**kw)
        self.name = normalize(name)
        self.value = normalize(value)

    def label(self) -> str:
        return f"let {describe(self.name)}"

    def execute(self, context: Scope) -> list[Action] | None:
        context.configurations[perform(self.name, context)] = perform(self.value, context)
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        if e.has("file") == e.has("value"):
            raise e.error("`let` takes either `value` or `file` (with optional `replace`)")
        if e.has("replace") and not e.has("file"):
            raise e.error("`replace` needs `file`", key="replace")
        if e.has("file"):
            replace = e.raw("replace") or {}
            if not isinstance(replace, Mapping):
                raise e.error("replace must map PLACEHOLDER: value", key="replace")
            value: Any = FileContent(e.text("file"), {str(k): e.parse(str(v)) for k, v in replace.items()})
        else:
            value = e.text("value")
        return cls(e.text("name", required=True), value)


@register
class UnsetLaunchConfiguration(Action):
    frontend_tags = ("unset",)
    frontend_attrs = ("name",)

    def __init__(self, name: SomeSubstitutions, **kw: Any) -> None:
        super().__init__(**kw)
        self.name = normalize(name)

    def label(self) -> str:
        return f"unset {describe(self.name)}"

    def execute(self, context: Scope) -> list[Action] | None:
        context.configurations.pop(perform(self.name, context), None)
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(e.text("name", required=True))


class PushLaunchConfigurations(Action):
    def execute(self, context: Scope) -> list[Action] | None:
        context.push_configurations()
        return None


class PopLaunchConfigurations(Action):
    def execute(self, context: Scope) -> list[Action] | None:
        context.pop_configurations()
        return None


class PushEnvironment(Action):
    def execute(self, context: Scope) -> list[Action] | None:
        context.push_environment()
        return None


class PopEnvironment(Action):
    def execute(self, context: Scope) -> list[Action] | None:
        context.pop_environment()
        return None


@register
class GroupAction(Action):
    """A group of actions; scoped by default, so configurations, environment and namespace stay inside."""

    frontend_tags = ("group",)
    frontend_attrs = ("scoped", "forwarding", "namespace", "keep", "children")

    def __init__(
        self,
        actions: Iterable[Action],
        *,
        scoped: bool = True,
        forwarding: bool = True,
        launch_configurations: Mapping[str, SomeSubstitutions] | None = None,
        namespace: SomeSubstitutions | None = None,
        **kw: Any,
    ) -> None:
        super().__init__(**kw)
        self.actions = list(actions)
        self.scoped = scoped
        self.forwarding = forwarding
        self.launch_configurations = {k: normalize(v) for k, v in (launch_configurations or {}).items()}
        self.namespace = None if namespace is None else normalize(namespace)

    def execute(self, context: Scope) -> list[Action] | None:
        # As ros2/launch's GroupAction: scoping is Push/Pop actions around the group's actions.
        sets: list[Action] = [SetLaunchConfiguration(k, v) for k, v in self.launch_configurations.items()]
        if self.namespace is not None:
            sets.append(PushRosNamespace(self.namespace))
        for action in sets:
            action.where = self.where
        if not self.scoped:
            return [*sets, *self.actions]
        if self.forwarding:
            return [
                PushLaunchConfigurations(),
                PushEnvironment(),
                *sets,
                *self.actions,
                PopEnvironment(),
                PopLaunchConfigurations(),
            ]
        keep = ResetLaunchConfigurations(self.launch_configurations)
        extra = [PushRosNamespace(self.namespace)] if self.namespace is not None else []
        return [
            PushLaunchConfigurations(),
            PushEnvironment(),
            ResetEnvironment(),
            keep,
            *extra,
            *self.actions,
            PopEnvironment(),
            PopLaunchConfigurations(),
        ]

    def describe_sub_entities(self) -> list[Action]:
        return list(self.actions)

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        keep = {
            k.plain("name", required=True): k.text("value", required=True) for k in e.items("keep", ("name", "value"))
        }
        return cls(
            e.children(),
            scoped=e.boolean("scoped", True),
            forwarding=e.boolean("forwarding", True),
            launch_configurations=keep,
            namespace=e.text("namespace"),
        )


@register
class PushRosNamespace(Action):
    frontend_tags = ("push_ros_namespace",)
    frontend_attrs = ("namespace",)

    def __init__(self, namespace: SomeSubstitutions, **kw: Any) -> None:
        super().__init__(**kw)
        self.namespace = normalize(namespace)

    def execute(self, context: Scope) -> list[Action] | None:
        context.push_namespace(perform(self.namespace, context))
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(e.text("namespace", required=True))


PushROSNamespace = PushRosNamespace


@register
class SetEnvironmentVariable(Action):
    frontend_tags = ("set_env",)
    frontend_attrs = ("name", "value")

    def __init__(self, name: SomeSubstitutions, value: SomeSubstitutions, **kw: Any) -> None:
        super().__init__(**kw)
        self.name = normalize(name)
        self.value = normalize(value)

    def execute(self, context: Scope) -> list[Action] | None:
        context.set_env(perform(self.name, context), perform(self.value, context))
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(e.text("name", required=True), e.text("value", required=True))


@register
class AppendEnvironmentVariable(Action):
    """`append_env`: add to a PATH-like variable (`prepend` puts it first), joined with `separator`."""

    frontend_tags = ("append_env",)
    frontend_attrs = ("name", "value", "prepend", "separator")

    def __init__(
        self,
        name: SomeSubstitutions,
        value: SomeSubstitutions,
        *,
        prepend: bool = False,
        separator: str = os.pathsep,
        **kw: Any,
    ) -> None:
        super().__init__(**kw)
        self.name, self.value = normalize(name), normalize(value)
        self.prepend, self.separator = prepend, separator

    def execute(self, context: Scope) -> list[Action] | None:
        scope = context
        name, value = perform(self.name, scope), perform(self.value, scope)
        old = scope.env.get(name)
        if old:
            value = f"{value}{self.separator}{old}" if self.prepend else f"{old}{self.separator}{value}"
        scope.set_env(name, value)
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(
            e.text("name", required=True),
            e.text("value", required=True),
            prepend=e.boolean("prepend", False),
            separator=e.plain("separator") or os.pathsep,
        )


@register
class UnsetEnvironmentVariable(Action):
    frontend_tags = ("unset_env",)
    frontend_attrs = ("name",)

    def __init__(self, name: SomeSubstitutions, **kw: Any) -> None:
        super().__init__(**kw)
        self.name = normalize(name)

    def execute(self, context: Scope) -> list[Action] | None:
        context.set_env(perform(self.name, context), None)
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(e.text("name", required=True))


@register
class ResetEnvironment(Action):
    """`reset_env`: the environment as it was when the launch started, for everything after it in this scope."""

    frontend_tags = ("reset_env",)

    def execute(self, context: Scope) -> list[Action] | None:
        context.reset_environment()
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls()


@register
class ResetLaunchConfigurations(Action):
    """`reset`: forget every launch configuration but the `<keep>` ones (evaluated before forgetting)."""

    frontend_tags = ("reset",)
    frontend_attrs = ("keep",)

    def __init__(self, launch_configurations: Mapping[str, SomeSubstitutions] | None = None, **kw: Any) -> None:
        super().__init__(**kw)
        self.keep = {k: normalize(v) for k, v in (launch_configurations or {}).items()}

    def execute(self, context: Scope) -> list[Action] | None:
        kept = {k: perform(v, context) for k, v in self.keep.items()}
        context.configurations.clear()
        context.configurations.update(kept)
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(
            {k.plain("name", required=True): k.text("value", required=True) for k in e.items("keep", ("name", "value"))}
        )


def seconds(text: str, what: str, *, allow_zero: bool = True) -> float:
    """A duration attribute → float seconds, rejecting negative, NaN and infinite values."""
    try:
        value = float(text)
    except (TypeError, ValueError):
        raise LaunchError(f"{what} {text!r} is not a number of seconds") from None
    if value != value or value in (float("inf"), float("-inf")) or value < 0 or (value == 0 and not allow_zero):
        raise LaunchError(f"{what} {text!r} must be a finite number of seconds " + ("≥ 0" if allow_zero else "> 0"))
    return value


@register
class TimerAction(Action):
    frontend_tags = ("timer",)
    frontend_attrs = ("period", "children", "cancel_on_shutdown")

    def __init__(
        self,
        *,
        period: SomeSubstitutions | float,
        actions: Iterable[Action],
        cancel_on_shutdown: bool = True,
        **kw: Any,
    ) -> None:
        super().__init__(**kw)
        self.period = normalize(period)
        self.actions = list(actions)
        self.cancel_on_shutdown = cancel_on_shutdown

    def label(self) -> str:
        return f"timer {describe(self.period)} s"

    def execute(self, context: Scope) -> list[Action] | None:
        engine = context.engine
        if engine.dry:
            # --print: the period and actions as they would be now; at run time both are evaluated when the
            # timer starts and fires, after the enclosing group is gone (as Jazzy's TimerAction).
            try:
                period = seconds(perform(self.period, context), "timer period")
            except LaunchError as e:
                engine.effect(Unknown(what=self.label(), why=f"its period is known only at run time: {e}"))
                period = float("nan")
            steps = engine.preview(self.actions)
            engine.effect(StartTimer(period_s=period, steps=steps, cancel_on_shutdown=self.cancel_on_shutdown))
            return None
        saved = context.get_locals_as_dict()

        def start() -> None:
            from diffctl.launch_legacy.events import TimerEvent

            period = seconds(perform(self.period, context), "timer period")
            kind = "timer" if self.cancel_on_shutdown else "timer-kept"  # the latter still fires during shutdown
            engine.services.after(period, lambda: engine.emit(TimerEvent(timer_action=self, locals=saved)), kind)

        engine.defer(start)
        return None

    completes_later = True

    def describe_sub_entities(self) -> list[Action]:
        return list(self.actions)

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(
            period=e.text("period", required=True),
            actions=e.children(),
            cancel_on_shutdown=e.boolean("cancel_on_shutdown", True),
        )


@register
class LogInfo(Action):
    frontend_tags = ("log",)
    frontend_attrs = ("message", "level")

    def __init__(self, *, msg: SomeSubstitutions, **kw: Any) -> None:
        super().__init__(**kw)
        self.msg = normalize(msg)

    def label(self) -> str:
        return f"log {describe(self.msg)!r}"

    def execute(self, context: Scope) -> list[Action] | None:
        context.engine.effect(LogMessage(message=perform(self.msg, context)))
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        level = e.plain("level")
        if level is not None and level.upper() != "INFO":
            raise e.error(f"log level {level!r} is not supported", key="level", hint="valid: INFO")
        return cls(msg=e.text("message", required=True))


@register
class Shutdown(Action):
    """Shut the whole launch down (the `required` idiom: `on_exit=Shutdown()` / `on_exit: shutdown`)."""

    frontend_tags = ("shutdown",)
    frontend_attrs = ("reason",)

    def __init__(self, *, reason: SomeSubstitutions | None = None, **kw: Any) -> None:
        super().__init__(**kw)
        self.reason = None if reason is None else normalize(reason)

    def execute(self, context: Scope) -> list[Action] | None:
        reason = perform(self.reason, context) if self.reason is not None else "reason not given"
        context.engine.effect(RequestShutdown(reason=reason))
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(reason=e.text("reason"))


def is_substitution_list(value: Any) -> bool:
    return isinstance(value, Substitution) or (
        isinstance(value, (list, tuple)) and any(isinstance(v, Substitution) for v in value)
    )


def walk_entities(root: Any) -> Iterable[Any]:
    """Every entity reachable without running anything: groups, includes' fixed parts, handlers', timers'."""
    stack = [root]
    seen: set[int] = set()
    while stack:
        entity = stack.pop()
        if id(entity) in seen or not isinstance(entity, Action):
            continue
        seen.add(id(entity))
        yield entity
        stack.extend(entity.describe_sub_entities())
        for extra in ("on_exit",):
            stack.extend(getattr(entity, extra, None) or [])
