"""`DeclareLaunchArgument` (`<arg>`): declare an argument of a launch description."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .. import logging as launch_logging
from ..action import Action
from ..frontend.entity import Entity
from ..frontend.expose import expose_action
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_action('arg')
class DeclareLaunchArgument(Action):
    """Declares the launch argument `name`, stored in the launch configuration of the same name.

    Declared arguments are listed by `LaunchDescription.get_launch_arguments()` (the command line's
    `name:=value`, an include's arguments). With `default_value` the argument is optional; without one,
    executing the action when no value was given is an error. With `choices`, a value outside them is an
    error. `name` and `description` are plain text, since they are shown before anything runs.
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
        self.__name = name
        self.__logger = launch_logging.get_logger('launch.actions.declare_launch_argument')
        self.__default_value = None if default_value is None else normalize_to_list_of_substitutions(default_value)
        if choices is not None:
            if len(choices) == 0:
                message = 'Provided choices arg is empty. Use None to ignore the choice list.'
                self.__logger.error(message)
                raise RuntimeError(message)
            plain_default = default_value is not None and not isinstance(default_value, (Substitution, list))
            if plain_default and default_value not in choices:
                message = f'Provided default_value "{default_value}" is not in provided choices "{choices}".'
                self.__logger.error(message)
                raise RuntimeError(message)
        if description is None:
            self.__description = 'no description given' if choices is None else 'One of: ' + str(choices)
        else:
            self.__description = description
            if choices is not None:
                if not self.__description.endswith('.'):
                    self.__description += '.'
                self.__description += ' Valid choices are: ' + str(choices)
        self.__choices = choices
        # set by LaunchDescription.get_launch_arguments(): whether a condition guards the declaration
        self._conditionally_included = False

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        kwargs['name'] = parser.escape_characters(entity.get_attr('name'))
        default_value = entity.get_attr('default', optional=True)
        if default_value is not None:
            kwargs['default_value'] = parser.parse_substitution(default_value)
        description = entity.get_attr('description', optional=True)
        if description is not None:
            kwargs['description'] = parser.escape_characters(description)
        choices = entity.get_attr('choice', data_type=list[Entity], optional=True)
        if choices is not None:
            kwargs['choices'] = [parser.escape_characters(choice.get_attr('value')) for choice in choices]
        return cls, kwargs

    @property
    def name(self) -> str:
        return self.__name

    @property
    def default_value(self) -> list[Substitution] | None:
        return self.__default_value

    @property
    def description(self) -> str:
        return self.__description

    @property
    def choices(self) -> list[str] | None:
        return self.__choices

    def execute(self, context: LaunchContext) -> None:
        configurations = context.launch_configurations
        if self.name not in configurations:
            if self.default_value is None:
                self.__logger.error(
                    f'Required launch argument "{self.name}" (description: "{self.description}") was not provided')
                raise RuntimeError(f'Required launch argument "{self.name}" was not provided.')
            configurations[self.name] = perform_substitutions(context, self.default_value)
        if self.__choices is not None and configurations[self.name] not in self.__choices:
            message = (f'Argument "{self.name}" provided value "{configurations[self.name]}" is not valid. '
                       f'Valid options are: {self.__choices}')
            self.__logger.error(message)
            raise RuntimeError(message)
