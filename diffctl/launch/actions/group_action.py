"""`GroupAction`, `<group [scoped=…] [forwarding=…]>`: actions under one condition, usually one scope."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from .._private.markup import kept_configurations
from ..action import Action
from ..frontend.expose import expose_action
from .pop_environment import PopEnvironment
from .pop_launch_configurations import PopLaunchConfigurations
from .push_environment import PushEnvironment
from .push_launch_configurations import PushLaunchConfigurations
from .reset_environment import ResetEnvironment
from .reset_launch_configurations import ResetLaunchConfigurations
from .set_launch_configuration import SetLaunchConfiguration

if TYPE_CHECKING:
    from ..frontend.entity import Entity
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext
    from ..launch_description_entity import LaunchDescriptionEntity
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_action('group')
class GroupAction(Action):
    """Visits `actions`, in a scope of their own unless `scoped` is false.

    In a scope, launch configurations and environment changes made by the actions are undone at its end.
    A scope `forwarding` (the default) starts from the current configurations and environment; otherwise
    from no configurations and the environment the launch began with. `launch_configurations` (name →
    value) are set first; without forwarding they are performed before the others are dropped.
    Without a scope nothing is undone.
    """

    def __init__(
        self,
        actions: Iterable[Action],
        *,
        scoped: bool = True,
        forwarding: bool = True,
        launch_configurations: dict[SomeSubstitutionsType, SomeSubstitutionsType] | None = None,
        **left_over_kwargs: Any,
    ) -> None:
        super().__init__(**left_over_kwargs)
        self._members = actions
        self._scope = (scoped, forwarding)
        self._settings = launch_configurations or {}
        self._expanded: list[LaunchDescriptionEntity] | None = None

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        for flag in ('scoped', 'forwarding'):
            value = entity.get_attr(flag, data_type=bool, optional=True)
            if value is not None:
                kwargs[flag] = value
        kept = kept_configurations(entity, parser)
        if kept is not None:
            kwargs['launch_configurations'] = kept
        kwargs['actions'] = [parser.parse_action(child) for child in entity.children if child.type_name != 'keep']
        return cls, kwargs

    def _expand(self) -> list[LaunchDescriptionEntity]:
        scoped, forwarding = self._scope
        body: list[LaunchDescriptionEntity] = list(self._members)
        if scoped and not forwarding:
            opening = [ResetEnvironment(), ResetLaunchConfigurations(self._settings)]
        else:
            opening = [SetLaunchConfiguration(name, value) for name, value in self._settings.items()]
        if not scoped:
            return opening + body
        return [
            PushLaunchConfigurations(), PushEnvironment(), *opening, *body, PopEnvironment(), PopLaunchConfigurations(),
        ]

    def get_sub_entities(self) -> list[LaunchDescriptionEntity]:
        # made once: describing and executing the group see the same entities
        if self._expanded is None:
            self._expanded = self._expand()
        return self._expanded

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity]:
        return self.get_sub_entities()
