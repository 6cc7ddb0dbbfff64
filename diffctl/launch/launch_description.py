"""`LaunchDescription`: the entities of a launch, and the arguments it declares."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

from . import logging as launch_logging
from .launch_description_entity import LaunchDescriptionEntity

if TYPE_CHECKING:
    from .action import Action
    from .actions.declare_launch_argument import DeclareLaunchArgument
    from .actions.include_launch_description import IncludeLaunchDescription
    from .launch_context import LaunchContext


class LaunchDescription(LaunchDescriptionEntity):
    """An ordered collection of entities; visiting it yields them.

    `get_launch_arguments()` finds the `DeclareLaunchArgument`s reachable without launching: in the
    entities, what they always yield, what they yield under a condition, and what included files declare
    (when they can be loaded without a context).
    """

    def __init__(
        self,
        initial_entities: Iterable[LaunchDescriptionEntity] | None = None,
        *,
        deprecated_reason: str | None = None,
    ) -> None:
        self.__entities = list(initial_entities) if initial_entities is not None else []
        self.__deprecated_reason = deprecated_reason

    def visit(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        if self.__deprecated_reason is not None:
            where = context.get_locals_as_dict().get('current_launch_file_path')
            if where is not None:
                message = f'launch file [{where}] is deprecated: {self.__deprecated_reason}'
            else:
                message = f'deprecated launch description: {self.__deprecated_reason}'
            launch_logging.get_logger().warning(message)
        return self.__entities

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        return self.__entities

    def get_launch_arguments(self, conditional_inclusion: bool = False) -> list[DeclareLaunchArgument]:
        """The declared arguments, first declaration of each name only (see the class doc)."""
        return [argument for argument, _ in
                self.get_launch_arguments_with_include_launch_description_actions(conditional_inclusion)]

    def get_launch_arguments_with_include_launch_description_actions(
        self, conditional_inclusion: bool = False
    ) -> list[tuple[DeclareLaunchArgument, list[IncludeLaunchDescription] | None]]:
        """(declaration, the includes it sits under, or None at this level) for each declared argument.

        Each declaration's `_conditionally_included` is set: whether a condition guards it (or
        `conditional_inclusion` for the top level). Declarations after a `ResetLaunchConfigurations`
        are not reachable by the caller's arguments and are not listed. Included files that cannot be
        loaded without a context are skipped.
        """
        from .actions.declare_launch_argument import DeclareLaunchArgument
        from .actions.include_launch_description import IncludeLaunchDescription
        from .actions.reset_launch_configurations import ResetLaunchConfigurations

        found: list[tuple[DeclareLaunchArgument, list[IncludeLaunchDescription] | None]] = []
        names = set()

        def walk(entities: Iterable[LaunchDescriptionEntity], conditional: bool,
                 includes: list[IncludeLaunchDescription] | None) -> None:
            for entity in entities:
                if isinstance(entity, DeclareLaunchArgument) and entity.name not in names:
                    names.add(entity.name)
                    entity._conditionally_included = conditional or entity.condition is not None
                    found.append((entity, includes))
                if isinstance(entity, ResetLaunchConfigurations):
                    return
                inner = includes
                if isinstance(entity, IncludeLaunchDescription):
                    inner = [*(includes or []), entity]
                walk(entity.describe_sub_entities(), False, inner)
                for _, conditional_entities in entity.describe_conditional_sub_entities():
                    walk(conditional_entities, True, inner)

        walk(self.entities, conditional_inclusion, None)
        return found

    @property
    def entities(self) -> list[LaunchDescriptionEntity]:
        return self.__entities

    def add_entity(self, entity: LaunchDescriptionEntity) -> None:
        """Append an entity."""
        self.__entities.append(entity)

    def add_action(self, action: Action) -> None:
        """Append an action."""
        self.add_entity(action)

    @property
    def deprecated(self) -> bool:
        return self.__deprecated_reason is not None

    @property
    def deprecated_reason(self) -> str | None:
        """Why this description is deprecated, or None when it is not."""
        return self.__deprecated_reason
