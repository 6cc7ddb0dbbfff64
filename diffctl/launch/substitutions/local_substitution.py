"""`LocalSubstitution`: something the context's locals hold, such as the event being handled."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..substitution import Substitution
from ..utilities.ensure_argument_type_impl import ensure_argument_type

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


class LocalSubstitution(Substitution):
    """`expression` read on `context.locals`: 'event.returncode' is `context.locals.event.returncode`.

    `description`, when given, is what `describe()` shows instead of the expression.
    """

    def __init__(self, expression: str, description: str | None = None) -> None:
        super().__init__()
        ensure_argument_type(expression, str, 'expression', 'LocalSubstitution')
        self._path = expression
        self._label = description

    @property
    def expression(self) -> str:
        return self._path

    @property
    def description(self) -> str | None:
        return self._label

    def describe(self) -> str:
        shown = self._path if self._label is None else self._label
        return f"LocalVar('{shown}')"

    def perform(self, context: LaunchContext) -> str:
        # an expression, not only a dotted path: 'event.cmd[0]' works as it does in ROS 2
        return eval(f'locals_.{self._path}', {}, {'locals_': context.locals})
