"""`IfElseSubstitution` (`$(if cond then [else])`): one of two values depending on a condition."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions
from ..utilities.type_utils import perform_typed_substitution
from .substitution_failure import SubstitutionFailure

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_substitution('if')
class IfElseSubstitution(Substitution):
    """`if_value` when `condition` reads as true, else `else_value`; at least one of them must be given.

    The condition is read as a boolean ('true', 'false', '1', '0', …); anything else is a
    SubstitutionFailure.
    """

    def __init__(
        self,
        condition: SomeSubstitutionsType,
        if_value: SomeSubstitutionsType = '',
        else_value: SomeSubstitutionsType = '',
    ) -> None:
        super().__init__()
        if if_value == else_value == '':
            raise RuntimeError('One of if_value and else_value must be specified')
        self._condition = normalize_to_list_of_substitutions(condition)
        self._if_value = normalize_to_list_of_substitutions(if_value)
        self._else_value = normalize_to_list_of_substitutions(else_value)

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        if not 2 <= len(data) <= 3:
            raise TypeError('if substitution expects from 2 or 3 arguments')
        kwargs = {'condition': data[0], 'if_value': data[1]}
        if len(data) == 3:
            kwargs['else_value'] = data[2]
        return cls, kwargs

    @property
    def condition(self) -> list[Substitution]:
        return self._condition

    @property
    def if_value(self) -> list[Substitution]:
        return self._if_value

    @property
    def else_value(self) -> list[Substitution]:
        return self._else_value

    def describe(self) -> str:
        return f'IfElseSubstitution({self.condition}, {self.if_value}, {self.else_value})'

    def perform(self, context: LaunchContext) -> str:
        try:
            condition = perform_typed_substitution(context, self.condition, bool)
        except (TypeError, ValueError) as e:
            raise SubstitutionFailure(e) from e
        return perform_substitutions(context, self.if_value if condition else self.else_value)
