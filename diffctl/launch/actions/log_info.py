"""`LogInfo` (`<log message=…>`): log a message."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .. import logging as launch_logging
from ..action import Action
from ..frontend.expose import expose_action
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions

if TYPE_CHECKING:
    from ..frontend.entity import Entity
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_action('log')
class LogInfo(Action):
    """Logs `msg` at INFO level on the 'launch.user' logger."""

    def __init__(self, *, msg: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__msg = normalize_to_list_of_substitutions(msg)
        self.__logger = launch_logging.get_logger('launch.user')

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        kwargs['msg'] = parser.parse_substitution(entity.get_attr('message'))
        return cls, kwargs

    @property
    def msg(self) -> list[Substitution]:
        return self.__msg

    def execute(self, context: LaunchContext) -> None:
        self.__logger.info(''.join(context.perform_substitution(sub) for sub in self.msg))
