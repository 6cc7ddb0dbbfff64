"""`LocalSubstitution`: a value from the context's locals, e.g. `LocalSubstitution('event.name')`."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..substitution import Substitution
from ..utilities.ensure_argument_type_impl import ensure_argument_type

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


class LocalSubstitution(Substitution):
    """The Python expression `expression` evaluated on `context.locals` (`'event.name'` → locals.event.name)."""

    def __init__(self, expression: str, description: str | None = None) -> None:
        super().__init__()
        ensure_argument_type(expression, str, 'expression', 'LocalSubstitution')
        self.__expression = expression
        self.__description = description

    @property
    def expression(self) -> str:
        return self.__expression

    @property
    def description(self) -> str | None:
        return self.__description

    def describe(self) -> str:
        return f"LocalVar('{self.expression if self.description is None else self.description}')"

    def perform(self, context: LaunchContext) -> str:
        return eval('context.locals.' + self.expression, {}, {'context': context})
