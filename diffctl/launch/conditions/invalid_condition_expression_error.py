"""`InvalidConditionExpressionError`: a condition's text is not a boolean."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..substitution import Substitution


class InvalidConditionExpressionError(ValueError):
    """The text a condition's substitutions gave (`expression`) is none of `valid_expressions`."""

    def __init__(
        self, expression: str, unexpanded_expression: list[Substitution], valid_expressions: list[str]
    ) -> None:
        accepted = ', '.join(valid_expressions)
        source = ' + '.join(str(piece) for piece in unexpanded_expression)
        super().__init__(
            f"invalid condition expression, expected one of [{accepted}] but got '{expression}', "
            f"expanded from '{source}'")
