"""`LaunchIntrospector`: a launch description as a tree of text, without running any of it."""

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
    """The lines, each with `indention` in front."""
    return [indention + line for line in lines]


def tree_like_indent(lines: list[str]) -> list[str]:
    """Lines indented by fours drawn as a tree: '├── ' where a line of the same depth or deeper follows,
    '└── ' elsewhere; lines not indented are left out."""
    kept = [(len(line) - len(line.lstrip()), line) for line in lines if line.startswith('    ')]
    drawn = []
    for index, (depth, line) in enumerate(kept):
        later = kept[index + 1][0] if index + 1 < len(kept) else -1
        lead = '│' + line[1:depth - 4] if depth > 4 else ''
        drawn.append(lead + ('├── ' if later >= depth else '└── ') + line[depth:])
    if drawn and drawn[-1].startswith('│'):
        drawn[-1] = ' ' + drawn[-1][1:]  # nothing below the last line to connect to
    return drawn


def format_substitutions(substitutions: SomeSubstitutionsType) -> str:
    """The substitutions' descriptions, joined by ' + '."""
    return ' + '.join(piece.describe() for piece in normalize_to_list_of_substitutions(substitutions))


def _process_line(process) -> str:
    def quoted(value):
        return value if value is None else f"'{format_substitutions(value)}'"

    def mapping(pairs):
        if pairs is None:
            return None
        return '{' + ', '.join(f'{format_substitutions(k)}: {format_substitutions(v)}' for k, v in pairs) + '}'

    words = ', '.join(format_substitutions(word) for word in process.cmd)
    where, environment = quoted(process.cwd), mapping(process.env)
    return f'ExecuteProcess(cmd=[{words}], cwd={where}, env={environment}, shell={process.shell})'


def format_action(action: Action) -> list[str]:
    """The lines describing an action: logs, events, processes and handler registrations in detail."""
    from .actions.emit_event import EmitEvent
    from .actions.execute_process import ExecuteProcess
    from .actions.log_info import LogInfo
    from .actions.register_event_handler import RegisterEventHandler

    if is_a(action, LogInfo):
        return [f'LogInfo({format_substitutions(action.msg)})']
    if is_a(action, EmitEvent):
        return [f"EmitEvent(event='{action.event.name}')"]
    if is_a(action, ExecuteProcess):
        return [_process_line(action)]
    if is_a(action, RegisterEventHandler):
        handler = action.event_handler
        return [f"RegisterEventHandler('{handler}'):", *indent(format_event_handler(handler))]
    return [f"Action('{action}')"]


def format_entities(entities: Iterable[LaunchDescriptionEntity]) -> list[str]:
    """The lines describing each entity: actions in detail, anything else by its text."""
    lines: list[str] = []
    for entity in entities:
        lines += format_action(entity) if is_a(entity, Action) else [f"Unknown entity('{entity}')"]
    return lines


def format_event_handler(event_handler: BaseEventHandler) -> list[str]:
    """A handler's description, with the entities it would give indented below it."""
    describe = getattr(event_handler, 'describe', None)
    if describe is None:
        return [f"EventHandler('{hex(id(event_handler))}')"]
    text, given = describe()
    if isinstance(given, LaunchDescriptionEntity):
        given = [given]
    return [text, *indent(format_entities(given))]


class LaunchIntrospector:
    """Describes launch descriptions in text (what `ros2 launch --print` prints)."""

    def format_launch_description(self, launch_description: LaunchDescription) -> str:
        """The description's repr, then its entities as a tree."""
        tree = tree_like_indent(indent(format_entities(launch_description.entities)))
        return '\n'.join([str(launch_description), *tree])
