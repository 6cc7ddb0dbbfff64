"""`IncludeLaunchDescription`, `<include file=…>` with `<arg name=… value=…/>` children."""

from __future__ import annotations

import os
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

from .. import logging as launch_logging
from .._private.markup import name_value_children
from ..action import Action
from ..frontend.expose import expose_action
from ..launch_description_source import LaunchDescriptionSource
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions
from .set_launch_configuration import SetLaunchConfiguration

if TYPE_CHECKING:
    from ..frontend.entity import Entity
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext
    from ..launch_description import LaunchDescription
    from ..launch_description_entity import LaunchDescriptionEntity
    from ..some_substitutions_type import SomeSubstitutionsType

Argument = tuple['SomeSubstitutionsType', 'SomeSubstitutionsType']


def _names(context: LaunchContext, arguments: Iterable[Argument]) -> list[str]:
    return [perform_substitutions(context, normalize_to_list_of_substitutions(name)) for name, _ in arguments]


@expose_action('include')
class IncludeLaunchDescription(Action):
    """Visits the launch description of a source (a file path is turned into one), with arguments.

    Every `(name, value)` of `launch_arguments` becomes a launch configuration before the description is
    visited, declared by it or not, and stays set afterwards (wrap the include in a group to scope it).
    The file's path and folder are the locals `current_launch_file_path` / `current_launch_file_directory`.
    An argument the description declares unconditionally without a default must be among the given ones
    (or among those of an include inside it): otherwise nothing of it runs and the launch fails.
    """

    def __init__(
        self,
        launch_description_source: LaunchDescriptionSource | SomeSubstitutionsType,
        *,
        launch_arguments: Iterable[Argument] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        if not isinstance(launch_description_source, LaunchDescriptionSource):
            from ..launch_description_sources.any_launch_description_source import AnyLaunchDescriptionSource

            launch_description_source = AnyLaunchDescriptionSource(launch_description_source)
        self._source = launch_description_source
        self._arguments = tuple(launch_arguments or ())

    @property
    def launch_description_source(self) -> LaunchDescriptionSource:
        return self._source

    @property
    def launch_arguments(self) -> Sequence[Argument]:
        return self._arguments

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        kwargs['launch_description_source'] = parser.parse_substitution(entity.get_attr('file'))
        arguments = name_value_children(entity, parser, 'arg')
        if arguments is not None:
            kwargs['launch_arguments'] = arguments
        return cls, kwargs

    def get_sub_entities(self) -> list[LaunchDescriptionEntity]:
        description = self._source.try_get_launch_description_without_context()
        return [] if description is None else [description]

    def _names_known_beforehand(self) -> list[str] | None:
        """The names of the arguments given, when they can be told without a running launch."""
        from ..launch_context import LaunchContext

        try:
            return _names(LaunchContext(), self._arguments)
        except Exception as problem:
            launch_logging.get_logger('launch.actions.include_launch_description').debug(
                'Failed to get launch arguments names for launch description '
                f"'{self._source.location}', with exception: {problem}")
            return None

    def _check_required(self, description: LaunchDescription, given: list[str]) -> None:
        for declaration, through in description.get_launch_arguments_with_include_launch_description_actions():
            if declaration._conditionally_included or declaration.default_value is not None:
                continue
            known = list(given)
            for nested in through or ():
                known += nested._names_known_beforehand() or []
            if declaration.name not in known:
                raise RuntimeError(
                    f"Included launch description missing required argument '{declaration.name}' "
                    f"(description: '{declaration.description}'), given: [{', '.join(known)}]")

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity]:
        description = self._source.get_launch_description(context)
        file_path = os.path.abspath(self._source.location)
        # a source that is no file ('<script>') passes its location on as the folder
        folder = os.path.dirname(file_path) if os.path.exists(file_path) else self._source.location
        context.extend_locals({'current_launch_file_path': file_path, 'current_launch_file_directory': folder})
        self._check_required(description, _names(context, self._arguments))
        return [*(SetLaunchConfiguration(name, value) for name, value in self._arguments), description]
