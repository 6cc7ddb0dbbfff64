"""Resolving a launch description into a plan: conditions, substitutions, includes, names, links.

Everything a real launch would trip over is found here, before any process starts: a missing argument,
an unknown package, substitution or process name, a missing file, an include cycle. `--print` shows the
result; the supervisor runs it.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import replace
from pathlib import Path
from typing import Any

from diffctl.errors import LaunchError, suggest
from diffctl.launch.actions import Action, DeclareLaunchArgument, GroupAction, LaunchDescription
from diffctl.launch.context import Scope
from diffctl.launch.event_handlers import YamlTarget
from diffctl.launch.include_action import IncludeLaunchDescription
from diffctl.launch.plan import (
    PROCESS_WAIT_KINDS,
    Argument,
    Gate,
    Plan,
    ProcessSpec,
    Skipped,
    Step,
    TargetRef,
    Wait,
    Where,
)
from diffctl.launch.substitutions import is_static, perform


class Resolver:
    def __init__(self, *, strict: bool = True) -> None:
        self.strict = strict
        self.processes: dict[str, ProcessSpec] = {}
        self.origin_names: dict[int, str] = {}
        self.process_actions: dict[str, Action] = {}  # for the `action` of events given to callables
        self.arguments: list[Argument] = []
        self.warnings: list[str] = []
        self._refs: list[tuple[TargetRef, bool, Where, str]] = []  # (ref, must exist, where, entity)
        self._current: tuple[Where, str] = (Where(), "")
        self._declared: list[list[str]] = []
        self._skipped = False

    # ---- entry points ----------------------------------------------------------------------------------------

    def resolve(self, description: LaunchDescription, arguments: dict[str, str], source: str) -> Plan:
        scope = Scope.initial(arguments, source)
        self._declared.append(declared_names(description))
        try:
            steps = self.visit_all(description.entities, scope)
        finally:
            self._declared.pop()
        self._link()
        return Plan(source, self.arguments, tuple(steps), dict(self.processes), list(self.warnings))

    def resolve_more(self, actions: Iterable[Action], scope: Scope) -> list[Step]:
        """Actions a callable handler or OpaqueFunction returned while the launch runs: resolved and linked."""
        steps = self.visit_all(actions, scope)
        self._link()
        return steps

    def include(self, path: Path, scope: Scope) -> list[Step]:
        from diffctl.launch.loader import load

        description = load(path)
        self._declared.append(declared_names(description))
        try:
            return self.visit_all(description.entities, scope)
        finally:
            self._declared.pop()

    # ---- walking ---------------------------------------------------------------------------------------------

    def visit_all(self, actions: Iterable[Action], scope: Scope) -> list[Step]:
        out: list[Step] = []
        for action in actions:
            out += self.visit(action, scope)
        return out

    def visit(self, action: Action, scope: Scope) -> list[Step]:
        try:
            if action.condition is not None and not action.condition.evaluate(scope):
                self._skipped = True
                return [Skipped(what=action.label(), condition=action.condition.describe(), where=str(action.where))]
            outer, self._current = self._current, (action.where, action.label())
            try:
                gate = self._gate(action, scope)
                steps = action.visit(self, scope)
            finally:
                self._current = outer
        except LaunchError as e:
            raise action.where.attach(e, action.label()) from None
        steps = [s if s.where else replace(s, where=str(action.where)) for s in steps]
        if gate is not None:
            steps = [s.with_gate(gate) for s in steps]
        return steps

    def _gate(self, action: Action, scope: Scope) -> Gate | None:
        if not action.wait_for:
            return None
        waits: list[Wait] = []
        for w in action.wait_for:
            if w.kind in PROCESS_WAIT_KINDS:
                waits.append(Wait(w.kind, self.ref(w.target, scope, must_exist=True), w.pattern))
            else:
                name = perform(w.target, scope)
                if not name.startswith("/"):
                    name = scope.namespace.rstrip("/") + "/" + name
                waits.append(Wait(w.kind, name))
        return Gate(tuple(waits), action.wait_timeout)

    # ---- bookkeeping used by actions -------------------------------------------------------------------------

    def add_process(self, action: Action, name: str, **fields: Any) -> ProcessSpec:
        if not name:
            raise LaunchError("a process needs a name")
        unique = name
        n = 2
        while unique in self.processes:
            unique = f"{name}-{n}"
            n += 1
        self.origin_names.setdefault(id(action), unique)
        spec = ProcessSpec(name=unique, where=str(action.where), origin=id(action), **fields)
        self.processes[unique] = spec
        self.process_actions[unique] = action
        return spec

    def ref(self, target: Any, scope: Scope, *, must_exist: bool = False) -> TargetRef:
        """A process named by a handler or readiness condition: an action object, or its name."""
        if isinstance(target, Action):
            ref = TargetRef(origin=id(target), label=target.label())
        elif isinstance(target, YamlTarget):
            ref = target.ref(scope)
        else:
            name = perform(target, scope)
            ref = TargetRef(name=name, label=name)
        self._refs.append((ref, must_exist, *self._current))
        return ref

    def declare(self, argument: Argument) -> None:
        if all(a.name != argument.name for a in self.arguments):
            self.arguments.append(argument)

    def missing_argument(self, name: str, scope: Scope) -> None:
        if not self.strict:
            return None
        declared = self._declared[-1] if self._declared else []
        raise LaunchError(
            f"missing required launch argument {name!r}",
            hint=f"pass {name}:=VALUE; declared arguments: " + ", ".join(declared),
        )

    def _link(self) -> None:
        names = sorted(self.processes)
        refs, self._refs = self._refs, []
        for ref, must_exist, where, entity in refs:
            if ref.origin is not None:
                ref.name = self.origin_names.get(ref.origin)
                if ref.name is None and must_exist:
                    raise where.attach(
                        LaunchError(
                            f"wait_for names {ref.label}, which this launch never starts",
                            hint="is it skipped by its condition?",
                        ),
                        entity,
                    )
                if ref.name is None:
                    # A process a callable may still return at run time: linked when it is resolved then.
                    self._refs.append((ref, must_exist, where, entity))
                continue
            if ref.name not in self.processes:
                message = f"unknown process {ref.name!r}{suggest(ref.name or '', names)}"
                if must_exist or not self._skipped:
                    error = LaunchError(message, hint="processes: " + (", ".join(names) or "none"))
                    raise where.attach(error, entity)
                self.warnings.append(f"{where}: {message} (its handler will never run)")


def declared_names(description: LaunchDescription) -> list[str]:
    return [a.name for a in _declarations(description.entities)]


def _declarations(actions: Iterable[Action]) -> Iterable[DeclareLaunchArgument]:
    for action in actions:
        if isinstance(action, DeclareLaunchArgument):
            yield action
        elif isinstance(action, (GroupAction,)):
            yield from _declarations(action.actions)
        elif isinstance(action, LaunchDescription):
            yield from _declarations(action.entities)


def declared_arguments(description: LaunchDescription, source: str) -> list[Argument]:
    """Arguments declared by a description and the files it includes by a fixed path (for --show-args)."""
    from diffctl.launch.loader import load

    out: list[Argument] = []
    seen: set[str] = set()

    def walk(desc: LaunchDescription, file: str, stack: tuple[str, ...]) -> None:
        scope = Scope.initial({}, file)
        for action in _flatten(desc.entities):
            if isinstance(action, DeclareLaunchArgument) and action.name not in seen:
                seen.add(action.name)
                default = None if action.default_value is None else _try_perform(action.default_value, scope)
                out.append(Argument(action.name, None, default, action.description, action.choices, file))
            elif isinstance(action, IncludeLaunchDescription) and is_static(action.location):
                path = Path(perform(action.location, scope))
                if not path.is_absolute():
                    path = Path(file).parent / path
                if path.is_file() and str(path.resolve()) not in stack:
                    walk(load(path), str(path.resolve()), (*stack, str(path.resolve())))

    walk(description, source, (source,))
    return out


def _flatten(actions: Iterable[Action]) -> Iterable[Action]:
    for action in actions:
        yield action
        if isinstance(action, GroupAction):
            yield from _flatten(action.actions)
        elif isinstance(action, LaunchDescription):
            yield from _flatten(action.entities)


def _try_perform(value: Any, scope: Scope) -> str:
    try:
        return perform(value, scope)
    except LaunchError:
        return "".join(s.describe() for s in value)


def resolve(description: LaunchDescription, arguments: dict[str, str], source: str) -> Plan:
    return Resolver().resolve(description, arguments, source)


__all__ = ["Resolver", "Where", "declared_arguments", "resolve"]
