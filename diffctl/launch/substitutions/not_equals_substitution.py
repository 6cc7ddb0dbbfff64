"""`NotEqualsSubstitution`, `$(not-equals a b)`: whether two values differ once performed."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from .._private.operands import bool_text
from ..frontend.expose import expose_substitution
from .equals_substitution import EqualsSubstitution

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


@expose_substitution('not-equals')
class NotEqualsSubstitution(EqualsSubstitution):
    """'true' exactly when `EqualsSubstitution` of the same sides gives 'false'."""

    def __init__(self, left: Any | Iterable[Any] | None, right: Any | Iterable[Any] | None) -> None:
        super().__init__(left, right)

    def describe(self) -> str:
        return f'NotEqualsSubstitution({self.left} {self.right})'

    def perform(self, context: LaunchContext) -> str:
        return bool_text(not self._equal(context))
