"""`GroupAction` (`<group>`): actions grouped under one condition and, by default, one scope."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from ..action import Action
from ..frontend.entity import Entity
from ..frontend.expose import expose_action
from ..launch_description_entity import LaunchDescriptionEntity
from .pop_environment import PopEnvironment
from .pop_launch_configurations import PopLaunchConfigurations
from .push_environment import PushEnvironment
from .push_launch_configurations import PushLaunchConfigurations
from .reset_environment import ResetEnvironment
from .reset_launch_configurations import ResetLaunchConfigurations, parse_keeps
from .set_launch_configuration import SetLaunchConfiguration

if TYPE_CHECKING:
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_action('group')
class GroupAction(Action):
    """Yields `actions`, optionally scoped and with launch configurations of their own.

    `scoped` (default): changes of launch configurations and environment made inside stay inside.
    `forwarding` (default): a scoped group starts from the current configurations and environment;
    without it, it starts from none (the configurations) and from the launch's initial environment.
    `launch_configurations` are set at the start of the group (without forwarding, evaluated before the
    configurations are cleared).
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
        self.__actions = actions
        self.__scoped = scoped
        self.__forwarding = forwarding
        self.__launch_configurations = launch_configurations if launch_configurations is not None else {}
        self.__actions_to_return: list[LaunchDescriptionEntity] | None = None

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        scoped = entity.get_attr('scoped', data_type=bool, optional=True)
        forwarding = entity.get_attr('forwarding', data_type=bool, optional=True)
        if scoped is not None:
            kwargs['scoped'] = scoped
        if forwarding is not None:
            kwargs['forwarding'] = forwarding
        keeps = parse_keeps(entity, parser)
        if keeps is not None:
            kwargs['launch_configurations'] = keeps
        kwargs['actions'] = [parser.parse_action(e) for e in entity.children if e.type_name != 'keep']
        return cls, kwargs

    def get_sub_entities(self) -> list[LaunchDescriptionEntity]:
        if self.__actions_to_return is None:
            actions = list(self.__actions)
            settings = [SetLaunchConfiguration(k, v) for k, v in self.__launch_configurations.items()]
            if not self.__scoped:
                self.__actions_to_return = [*settings, *actions]
            elif self.__forwarding:
                self.__actions_to_return = [
                    PushLaunchConfigurations(), PushEnvironment(), *settings, *actions,
                    PopEnvironment(), PopLaunchConfigurations(),
                ]
            else:
                self.__actions_to_return = [
                    PushLaunchConfigurations(), PushEnvironment(), ResetEnvironment(),
                    ResetLaunchConfigurations(self.__launch_configurations), *actions,
                    PopEnvironment(), PopLaunchConfigurations(),
                ]
        return self.__actions_to_return

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        return self.get_sub_entities()
