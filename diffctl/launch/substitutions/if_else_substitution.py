"""`IfElseSubstitution`, `$(if cond then [else])`: a choice between two values on a boolean."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from .._private.operands import tag_kwargs, truth_of
from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_substitution('if')
class IfElseSubstitution(Substitution):
    """`if_value` when `condition` is true, `else_value` when it is false; both default to ''.

    Giving neither is an error at construction. The condition is read like any boolean operand; other
    text fails the substitution.
    """

    def __init__(
        self,
        condition: SomeSubstitutionsType,
        if_value: SomeSubstitutionsType = '',
        else_value: SomeSubstitutionsType = '',
    ) -> None:
        super().__init__()
        if if_value == '' and else_value == '':
            raise RuntimeError('One of if_value and else_value must be specified')
        self._branches = {
            None: normalize_to_list_of_substitutions(condition),
            True: normalize_to_list_of_substitutions(if_value),
            False: normalize_to_list_of_substitutions(else_value),
        }

    @property
    def condition(self) -> list[Substitution]:
        return self._branches[None]

    @property
    def if_value(self) -> list[Substitution]:
        return self._branches[True]

    @property
    def else_value(self) -> list[Substitution]:
        return self._branches[False]

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        kwargs = tag_kwargs(
            data, ('condition', 'if_value', 'else_value'), 'if substitution expects from 2 or 3 arguments',
            required=2)
        return cls, kwargs

    def describe(self) -> str:
        return f'IfElseSubstitution({self.condition}, {self.if_value}, {self.else_value})'

    def perform(self, context: LaunchContext) -> str:
        chosen = self._branches[truth_of(context, self.condition)]
        return perform_substitutions(context, chosen)
