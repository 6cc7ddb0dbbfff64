"""`UnlessCondition`: an action runs when an expression says false."""

from __future__ import annotations

from .if_condition import IfCondition


class UnlessCondition(IfCondition):
    """Holds when `predicate_expression` performs to 'false' or '0'; the mirror image of IfCondition."""

    _holds_when = False
