"""`PathJoinSubstitution`: a path built from pieces, some of them substitutions."""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import TYPE_CHECKING

from .._private.operands import joined
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


class PathJoinSubstitution(Substitution):
    """The performed pieces joined by `os.path.join` (an absolute piece restarts the path, as there)."""

    def __init__(self, substitutions: Iterable[str | Substitution]) -> None:
        self._pieces = normalize_to_list_of_substitutions(substitutions)

    @property
    def substitutions(self) -> Iterable[Substitution]:
        return self._pieces

    def describe(self) -> str:
        return f"PathJoin('{joined(self._pieces)}')"

    def perform(self, context: LaunchContext) -> str:
        return os.path.join(*[piece.perform(context) for piece in self._pieces])
