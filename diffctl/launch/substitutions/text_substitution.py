"""`TextSubstitution`: a fixed piece of text among substitutions."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..substitution import Substitution

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


class TextSubstitution(Substitution):
    """`text` itself, whatever the context."""

    def __init__(self, *, text: str) -> None:
        super().__init__()
        if not isinstance(text, str):
            raise TypeError(f"TextSubstitution expected Text object got '{type(text)}' instead.")
        self._literal = text

    @property
    def text(self) -> str:
        return self._literal

    def describe(self) -> str:
        return f"'{self._literal}'"

    def perform(self, context: LaunchContext) -> str:
        return self._literal
