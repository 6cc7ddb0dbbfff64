"""`IfCondition`: an action runs when an expression says true."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..condition import Condition
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from .evaluate_condition_expression_impl import evaluate_condition_expression

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


class IfCondition(Condition):
    """Holds when `predicate_expression` performs to 'true' or '1' (any case, blanks ignored).

    'false' and '0' make it fail; other text raises InvalidConditionExpressionError on evaluation.
    """

    # the truth value of the expression for which the condition holds (UnlessCondition flips it)
    _holds_when = True

    def __init__(self, predicate_expression: SomeSubstitutionsType) -> None:
        self._expression = normalize_to_list_of_substitutions(predicate_expression)
        super().__init__(predicate=self._check)

    def _check(self, context: LaunchContext) -> bool:
        return evaluate_condition_expression(context, self._expression) is self._holds_when
