"""`evaluate_condition_expression`: the boolean a condition's text stands for."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..utilities.perform_substitutions_impl import perform_substitutions
from .invalid_condition_expression_error import InvalidConditionExpressionError

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..substitution import Substitution

VALID_TRUE_EXPRESSIONS = ['true', '1']
VALID_FALSE_EXPRESSIONS = ['false', '0']


def evaluate_condition_expression(context: LaunchContext, expression: list[Substitution]) -> bool:
    """True for 'true' or '1', False for 'false' or '0' (after stripping, any case); else raises.

    :raises: InvalidConditionExpressionError
    """
    text = perform_substitutions(context, expression).strip().lower()
    if text in VALID_TRUE_EXPRESSIONS:
        return True
    if text in VALID_FALSE_EXPRESSIONS:
        return False
    raise InvalidConditionExpressionError(text, expression, VALID_TRUE_EXPRESSIONS + VALID_FALSE_EXPRESSIONS)
