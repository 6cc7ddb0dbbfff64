"""`IncludeLaunchDescription` (`<include>`): run another launch description, with arguments."""

from __future__ import annotations

import os
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

from .. import logging as launch_logging
from ..action import Action
from ..frontend.entity import Entity
from ..frontend.expose import expose_action
from ..launch_description_entity import LaunchDescriptionEntity
from ..launch_description_source import LaunchDescriptionSource
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions
from .set_launch_configuration import SetLaunchConfiguration

if TYPE_CHECKING:
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_action('include')
class IncludeLaunchDescription(Action):
    """Yields the launch description of a source (or a file path), after setting its arguments.

    Each `(name, value)` of `launch_arguments` becomes a launch configuration (declared by the included
    description or not). An unconditional argument the included description declares without a default,
    and which is not given, is an error raised before anything of it runs.
    """

    def __init__(
        self,
        launch_description_source: LaunchDescriptionSource | SomeSubstitutionsType,
        *,
        launch_arguments: Iterable[tuple[SomeSubstitutionsType, SomeSubstitutionsType]] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        if not isinstance(launch_description_source, LaunchDescriptionSource):
            from ..launch_description_sources.any_launch_description_source import AnyLaunchDescriptionSource

            launch_description_source = AnyLaunchDescriptionSource(launch_description_source)
        self.__launch_description_source = launch_description_source
        self.__launch_arguments = () if launch_arguments is None else tuple(launch_arguments)
        self.__logger = launch_logging.get_logger('launch.actions.include_launch_description')

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        kwargs['launch_description_source'] = parser.parse_substitution(entity.get_attr('file'))
        args = entity.get_attr('arg', data_type=list[Entity], optional=True)
        if args is not None:
            kwargs['launch_arguments'] = [
                (parser.parse_substitution(e.get_attr('name')), parser.parse_substitution(e.get_attr('value')))
                for e in args
            ]
            for e in args:
                e.assert_entity_completely_parsed()
        return cls, kwargs

    @property
    def launch_description_source(self) -> LaunchDescriptionSource:
        return self.__launch_description_source

    @property
    def launch_arguments(self) -> Sequence[tuple[SomeSubstitutionsType, SomeSubstitutionsType]]:
        return self.__launch_arguments

    def _get_launch_file(self) -> str:
        return os.path.abspath(self.__launch_description_source.location)

    def _get_launch_file_directory(self) -> str:
        path = self._get_launch_file()
        if os.path.exists(path):
            return os.path.dirname(path)
        # not a file (e.g. '<script>'): pass the location on as it is
        return self.__launch_description_source.location

    def get_sub_entities(self) -> list[LaunchDescriptionEntity]:
        description = self.__launch_description_source.try_get_launch_description_without_context()
        return [description] if description is not None else []

    def _try_get_arguments_names_without_context(self) -> list[str] | None:
        from ..launch_context import LaunchContext

        try:
            context = LaunchContext()
            return [
                perform_substitutions(context, normalize_to_list_of_substitutions(name))
                for name, _ in self.__launch_arguments
            ]
        except Exception as exc:
            self.__logger.debug(
                'Failed to get launch arguments names for launch description '
                f"'{self.__launch_description_source.location}', with exception: {exc!s}")
        return None

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity]:
        description = self.__launch_description_source.get_launch_description(context)
        context.extend_locals({'current_launch_file_path': self._get_launch_file()})
        context.extend_locals({'current_launch_file_directory': self._get_launch_file_directory()})

        given = [
            perform_substitutions(context, normalize_to_list_of_substitutions(name))
            for name, _ in self.launch_arguments
        ]
        for argument, includes in description.get_launch_arguments_with_include_launch_description_actions():
            if argument._conditionally_included or argument.default_value is not None:
                continue
            names = list(given)
            for include in includes or ():
                names.extend(include._try_get_arguments_names_without_context() or [])
            if argument.name not in names:
                raise RuntimeError(
                    "Included launch description missing required argument '{}' "
                    "(description: '{}'), given: [{}]".format(argument.name, argument.description, ', '.join(names)))

        settings = [SetLaunchConfiguration(name, value) for name, value in self.launch_arguments]
        return [*settings, description]
