"""The dry run: the engine walks a description with a recorder for services, giving the plan `--print` shows.

Nothing starts and no event happens; each handler's and timer's actions are previewed in a copy of the
context as it is when they are registered (at run time they are evaluated when they fire, and may differ:
what cannot be known before, e.g. a file a process will write, is shown as such). Everything a launch would
trip over in its first visit is found here: a missing argument, an unknown package, substitution or process
name, a missing file, an include cycle.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any

from diffctl.errors import LaunchError
from diffctl.launch_legacy.actions import Action, DeclareLaunchArgument, GroupAction, LaunchDescription
from diffctl.launch_legacy.context import LaunchContext
from diffctl.launch_legacy.engine import Engine, PlanRecorder
from diffctl.launch_legacy.include_action import IncludeLaunchDescription
from diffctl.launch_legacy.plan import Argument, Plan, Where
from diffctl.launch_legacy.substitutions import is_static, perform


class Resolver:
    """`Resolver().resolve(description, arguments, source)` → the plan of a dry run."""

    def resolve(self, description: LaunchDescription, arguments: dict[str, str], source: str) -> Plan:
        recorder = PlanRecorder()
        engine = Engine(dict(arguments), source, recorder, dry=True)
        engine.run_description(description)
        engine._link(final=True)
        return Plan(
            source,
            engine.arguments,
            tuple(recorder.steps),
            dict(engine.processes),
            list(engine.warnings),
            description=description,
            launch_arguments=dict(arguments),
        )


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
    from diffctl.launch_legacy.loader import load

    out: list[Argument] = []
    seen: set[str] = set()

    def walk(desc: LaunchDescription, file: str, stack: tuple[str, ...]) -> None:
        scope = LaunchContext({}, file)
        for action in _flatten(desc.entities):
            if isinstance(action, DeclareLaunchArgument) and action.name not in seen:
                seen.add(action.name)
                default = None if action.default_value is None else _try_perform(action.default_value, scope)
                subs = None if action.default_value is None else tuple(action.default_value)
                out.append(Argument(action.name, None, default, action.description, action.choices, file, subs))
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


def _try_perform(value: Any, scope: LaunchContext) -> str:
    try:
        return perform(value, scope)
    except LaunchError:
        return "".join(s.describe() for s in value)


def resolve(description: LaunchDescription, arguments: dict[str, str], source: str) -> Plan:
    return Resolver().resolve(description, arguments, source)


__all__ = ["Resolver", "Where", "declared_arguments", "resolve"]
