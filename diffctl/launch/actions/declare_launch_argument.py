"""`DeclareLaunchArgument`, `<arg name=… [default=…] [description=…]>` with `<choice value=…/>` children."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, NoReturn

from .. import logging as launch_logging
from ..action import Action
from ..frontend.expose import expose_action
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..frontend.entity import Entity
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType



def _complain(message: str) -> None:
    # ROS 2 logs these besides raising them: `ros2 launch` users see them even where the error is caught
    launch_logging.get_logger('launch.actions.declare_launch_argument').error(message)


def _refuse(message: str) -> NoReturn:
    _complain(message)
    raise RuntimeError(message)


def _help_text(description: str | None, choices: list[str] | None) -> str:
    """The description shown by `--show-args`; choices are spelled out in it."""
    if description is None:
        return 'no description given' if choices is None else f'One of: {choices}'
    if choices is None:
        return description
    stop = '' if description.endswith('.') else '.'
    return f'{description}{stop} Valid choices are: {choices}'


@expose_action('arg')
class DeclareLaunchArgument(Action):
    """An argument of the launch description: the launch configuration `name`, given from outside.

    `LaunchDescription.get_launch_arguments()` lists the declarations (the command line's `name:=value`
    and an include's arguments fill them). When executed, a configuration already set wins; otherwise
    `default_value` is used, and without one the launch fails. A value outside `choices` fails too.
    `name` and `description` are plain text: they are shown before anything runs.
    """

    def __init__(
        self,
        name: str,
        *,
        default_value: SomeSubstitutionsType | None = None,
        description: str | None = None,
        choices: list[str] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        if choices is not None:
            if not choices:
                _refuse('Provided choices arg is empty. Use None to ignore the choice list.')
            literal = default_value is not None and not isinstance(default_value, (Substitution, list))
            if literal and default_value not in choices:
                _refuse(f'Provided default_value "{default_value}" is not in provided choices "{choices}".')
        self._argument = name
        self._fallback = None if default_value is None else normalize_to_list_of_substitutions(default_value)
        self._help = _help_text(description, choices)
        self._allowed = choices
        # whether a condition guards the declaration; LaunchDescription.get_launch_arguments() sets it, and
        # ROS 2's tools (ros2 launch --show-args, launch_testing) read it under this name
        self._conditionally_included = False

    @property
    def name(self) -> str:
        return self._argument

    @property
    def default_value(self) -> list[Substitution] | None:
        return self._fallback

    @property
    def description(self) -> str:
        return self._help

    @property
    def choices(self) -> list[str] | None:
        return self._allowed

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        from ..frontend.entity import Entity as EntityType

        _, kwargs = super().parse(entity, parser)
        kwargs['name'] = parser.escape_characters(entity.get_attr('name'))
        readers = {'default': ('default_value', parser.parse_substitution),
                   'description': ('description', parser.escape_characters)}
        for attribute, (keyword, read) in readers.items():
            text = entity.get_attr(attribute, optional=True)
            if text is not None:
                kwargs[keyword] = read(text)
        options = entity.get_attr('choice', data_type=list[EntityType], optional=True)
        if options is not None:
            kwargs['choices'] = [parser.escape_characters(option.get_attr('value')) for option in options]
        return cls, kwargs

    def execute(self, context: LaunchContext) -> None:
        table = context.launch_configurations
        if self._argument not in table:
            if self._fallback is None:
                _complain(
                    f'Required launch argument "{self._argument}" (description: "{self._help}") was not provided')
                raise RuntimeError(f'Required launch argument "{self._argument}" was not provided.')
            table[self._argument] = perform_substitutions(context, self._fallback)
        given = table[self._argument]
        if self._allowed is not None and given not in self._allowed:
            _refuse(
                f'Argument "{self._argument}" provided value "{given}" is not valid. '
                f'Valid options are: {self._allowed}')
