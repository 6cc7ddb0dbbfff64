"""`LaunchIntrospector`: a launch description as an indented tree of text, without running anything."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

from .action import Action
from .launch_description_entity import LaunchDescriptionEntity
from .utilities.class_tools_impl import is_a
from .utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions

if TYPE_CHECKING:
    from .event_handler import BaseEventHandler
    from .launch_description import LaunchDescription
    from .some_substitutions_type import SomeSubstitutionsType


def indent(lines: list[str], indention: str = '    ') -> list[str]:
    """Each line with `indention` in front."""
    return [f'{indention}{line}' for line in lines]


def tree_like_indent(lines: list[str]) -> list[str]:
    """Turn four-space indentation into tree branches ('├── ', '└── ', '│')."""
    result: list[str] = []
    previous_depth = None
    for line in lines:
        if not line.startswith('    '):
            continue
        depth = len(line) - len(line.lstrip())
        if previous_depth is not None and '└' in result[-1] and previous_depth <= depth:
            result[-1] = result[-1].replace('└', '├', 1)
        previous_depth = depth
        drawn = '│' + line[1:]
        result.append(drawn[:depth - 4] + '└── ' + drawn[depth:])
    if result and result[-1].startswith('│'):
        result[-1] = ' ' + result[-1][1:]
    return result


def format_entities(entities: Iterable[LaunchDescriptionEntity]) -> list[str]:
    """Lines describing each entity (actions in detail, anything else by its text)."""
    lines: list[str] = []
    for entity in entities:
        if is_a(entity, Action):
            lines.extend(format_action(entity))
        else:
            lines.append(f"Unknown entity('{entity}')")
    return lines


def format_substitutions(substitutions: SomeSubstitutionsType) -> str:
    """The substitutions' descriptions joined by ' + '."""
    return ' + '.join(sub.describe() for sub in normalize_to_list_of_substitutions(substitutions))


def format_event_handler(event_handler: BaseEventHandler) -> list[str]:
    """The handler's description, with the entities it would yield indented under it."""
    if not hasattr(event_handler, 'describe'):
        return [f"EventHandler('{hex(id(event_handler))}')"]
    text, entities = event_handler.describe()
    if isinstance(entities, LaunchDescriptionEntity):
        entities = [entities]
    return [text, *indent(format_entities(entities))]


def format_action(action: Action) -> list[str]:
    """Lines describing an action; log, emit, process and handler registrations in detail."""
    from .actions.emit_event import EmitEvent
    from .actions.execute_process import ExecuteProcess
    from .actions.log_info import LogInfo
    from .actions.register_event_handler import RegisterEventHandler

    if is_a(action, LogInfo):
        return [f'LogInfo({format_substitutions(action.msg)})']
    if is_a(action, EmitEvent):
        return [f"EmitEvent(event='{action.event.name}')"]
    if is_a(action, ExecuteProcess):
        cwd = action.cwd if action.cwd is None else f"'{format_substitutions(action.cwd)}'"
        env = action.env if action.env is None else '{' + ', '.join(
            f'{format_substitutions(k)}: {format_substitutions(v)}' for k, v in action.env) + '}'
        return ['ExecuteProcess(cmd=[{}], cwd={}, env={}, shell={})'.format(
            ', '.join(format_substitutions(x) for x in action.cmd), cwd, env, action.shell)]
    if is_a(action, RegisterEventHandler):
        return [
            f"RegisterEventHandler('{action.event_handler}'):",
            *indent(format_event_handler(action.event_handler)),
        ]
    return [f"Action('{action}')"]


class LaunchIntrospector:
    """Describes launch descriptions as text."""

    def format_launch_description(self, launch_description: LaunchDescription) -> str:
        """The description's text: its repr, then its entities as a tree."""
        lines = tree_like_indent(indent(format_entities(launch_description.entities)))
        return f'{launch_description}\n' + '\n'.join(lines)
