"""`LogInfo`, `<log message=…/>`: a line in the launch's log."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .. import logging as launch_logging
from .._private.markup import substitution_attributes
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


@expose_action('log')
class LogInfo(Action):
    """Writes `msg`, performed, at INFO level on the `launch.user` logger (screen and launch.log)."""

    def __init__(self, *, msg: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self._text = normalize_to_list_of_substitutions(msg)

    @property
    def msg(self) -> list[Substitution]:
        return self._text

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        kwargs.update(substitution_attributes(entity, parser, ('message',), renamed={'message': 'msg'}))
        return cls, kwargs

    def execute(self, context: LaunchContext) -> None:
        launch_logging.get_logger('launch.user').info(perform_substitutions(context, self._text))
