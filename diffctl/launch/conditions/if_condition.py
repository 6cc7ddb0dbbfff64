"""`IfCondition`: true when an expression reads as true."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..condition import Condition
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from .evaluate_condition_expression_impl import evaluate_condition_expression

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


class IfCondition(Condition):
    """True when `predicate_expression` (text and substitutions) is 'true' or '1', false for 'false' or '0'.

    Any other text raises `InvalidConditionExpressionError` when evaluated.
    """

    def __init__(self, predicate_expression: SomeSubstitutionsType) -> None:
        self.__predicate_expression = normalize_to_list_of_substitutions(predicate_expression)
        super().__init__(predicate=self._predicate_func)

    def _predicate_func(self, context: LaunchContext) -> bool:
        return evaluate_condition_expression(context, self.__predicate_expression)

    def describe(self) -> str:
        return self.__repr__()
