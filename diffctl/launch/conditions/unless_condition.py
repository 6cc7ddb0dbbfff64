"""`UnlessCondition`: true when an expression reads as false."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .if_condition import IfCondition

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


class UnlessCondition(IfCondition):
    """The negation of `IfCondition`, with the same reading of the expression."""

    def __init__(self, predicate_expression: SomeSubstitutionsType) -> None:
        super().__init__(predicate_expression)

    def _predicate_func(self, context: LaunchContext) -> bool:
        return not super()._predicate_func(context)

    def describe(self) -> str:
        return self.__repr__()
