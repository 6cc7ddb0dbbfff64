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

Declaration = tuple['DeclareLaunchArgument', 'list[IncludeLaunchDescription] | None']


class _ArgumentSearch:
    """Finds the argument declarations of a tree of entities, as far as it is known without launching.

    It walks what entities always give and, marked conditional, what they give under a condition;
    included files count when they load without a context. A ResetLaunchConfigurations ends the walk of
    its level: what follows it cannot be set from outside.
    """

    def __init__(self) -> None:
        self.found: list[Declaration] = []
        self.seen: set[str] = set()

    def walk(self, entities: Iterable[LaunchDescriptionEntity], conditional: bool,
             through: list[IncludeLaunchDescription] | None) -> None:
        from .actions.declare_launch_argument import DeclareLaunchArgument
        from .actions.include_launch_description import IncludeLaunchDescription
        from .actions.reset_launch_configurations import ResetLaunchConfigurations

        for entity in entities:
            if isinstance(entity, DeclareLaunchArgument) and entity.name not in self.seen:
                self.seen.add(entity.name)
                # tools (--show-args, launch_testing) read this flag on the declaration itself
                entity._conditionally_included = conditional or entity.condition is not None
                self.found.append((entity, through))
            if isinstance(entity, ResetLaunchConfigurations):
                return
            below = [*(through or []), entity] if isinstance(entity, IncludeLaunchDescription) else through
            self.walk(entity.describe_sub_entities(), False, below)
            for _, maybe in entity.describe_conditional_sub_entities():
                self.walk(maybe, True, below)


class LaunchDescription(LaunchDescriptionEntity):
    """A list of entities, visited in order; it declares the arguments its DeclareLaunchArguments name.

    `deprecated_reason`, when given, is warned about each time the description is visited.
    """

    def __init__(
        self,
        initial_entities: Iterable[LaunchDescriptionEntity] | None = None,
        *,
        deprecated_reason: str | None = None,
    ) -> None:
        self._members: list[LaunchDescriptionEntity] = list(initial_entities or [])
        self._deprecation = deprecated_reason

    @property
    def entities(self) -> list[LaunchDescriptionEntity]:
        return self._members

    @property
    def deprecated(self) -> bool:
        return self._deprecation is not None

    @property
    def deprecated_reason(self) -> str | None:
        return self._deprecation

    def add_entity(self, entity: LaunchDescriptionEntity) -> None:
        self._members.append(entity)

    def add_action(self, action: Action) -> None:
        self._members.append(action)

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        return self._members

    def visit(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        if self._deprecation is not None:
            path = context.get_locals_as_dict().get('current_launch_file_path')
            what = 'deprecated launch description' if path is None else f'launch file [{path}] is deprecated'
            launch_logging.get_logger().warning(f'{what}: {self._deprecation}')
        return self._members

    def get_launch_arguments_with_include_launch_description_actions(
        self, conditional_inclusion: bool = False
    ) -> list[Declaration]:
        """Each argument declared (first declaration of a name), with the includes it is declared under.

        The includes are None for a declaration of this description itself. `conditional_inclusion` marks
        this level as conditional; every declaration's `_conditionally_included` is set on the way.
        """
        search = _ArgumentSearch()
        search.walk(self._members, conditional_inclusion, None)
        return search.found

    def get_launch_arguments(self, conditional_inclusion: bool = False) -> list[DeclareLaunchArgument]:
        """The arguments declared, here and in what is included (first declaration of a name only)."""
        return [declaration for declaration, _ in
                self.get_launch_arguments_with_include_launch_description_actions(conditional_inclusion)]
