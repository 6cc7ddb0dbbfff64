"""`InvalidConditionExpressionError`: a condition's text is neither true nor false."""

from __future__ import annotations

from ..substitution import Substitution


class InvalidConditionExpressionError(ValueError):
    """Raised when a condition expression expands to text that is not a boolean."""

    def __init__(
        self, expression: str, unexpanded_expression: list[Substitution], valid_expressions: list[str]
    ) -> None:
        super().__init__(
            "invalid condition expression, expected one of [{}] but got '{}', expanded from '{}'".format(
                ', '.join(valid_expressions), expression, ' + '.join(str(sub) for sub in unexpanded_expression)))
