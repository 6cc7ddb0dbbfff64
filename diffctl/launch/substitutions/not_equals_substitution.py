"""`NotEqualsSubstitution` (`$(not-equals a b)`): 'true' when two values differ."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from ..frontend.expose import expose_substitution
from .equals_substitution import EqualsSubstitution

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


@expose_substitution('not-equals')
class NotEqualsSubstitution(EqualsSubstitution):
    """The negation of `EqualsSubstitution`, with the same comparison rules."""

    def __init__(self, left: Any | Iterable[Any] | None, right: Any | Iterable[Any] | None) -> None:
        super().__init__(left, right)

    def describe(self) -> str:
        return f'NotEqualsSubstitution({self.left} {self.right})'

    def perform(self, context: LaunchContext) -> str:
        return 'false' if super().perform(context) == 'true' else 'true'
