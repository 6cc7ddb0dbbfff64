"""`evaluate_condition_expression`: the truth value a condition's text spells."""

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
    """Perform `expression` and read it, ignoring case and surrounding blanks: 'true'/'1' or 'false'/'0'.

    Any other text raises InvalidConditionExpressionError, which lists the accepted spellings.
    """
    spelled = perform_substitutions(context, expression).strip().lower()
    for accepted, meaning in ((VALID_TRUE_EXPRESSIONS, True), (VALID_FALSE_EXPRESSIONS, False)):
        if spelled in accepted:
            return meaning
    raise InvalidConditionExpressionError(spelled, expression, [*VALID_TRUE_EXPRESSIONS, *VALID_FALSE_EXPRESSIONS])
