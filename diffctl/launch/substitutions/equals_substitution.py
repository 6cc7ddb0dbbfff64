"""`EqualsSubstitution`, `$(equals a b)`: whether two values are the same once performed."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

from .._private.operands import bool_text, tag_kwargs
from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.type_utils import is_substitution, perform_substitutions

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType

_TRUE_WORDS = frozenset(('true', '1'))
_BOOL_WORDS = _TRUE_WORDS | {'false', '0'}


def _operand(value: Any) -> list[Substitution]:
    """Substitutions from a side given as anything: None is empty text, booleans are 'true'/'false'."""
    if not is_substitution(value):
        if value is None:
            value = ''
        elif isinstance(value, bool):
            value = bool_text(value)
        else:
            value = str(value)
    return normalize_to_list_of_substitutions(value)


def _number(text: str) -> float | None:
    try:
        return float(text)
    except ValueError:
        return None


def texts_equal(a: str, b: str) -> bool:
    """Two performed texts compared as booleans when both spell one, as numbers when both are, else as text."""
    if a.lower() in _BOOL_WORDS and b.lower() in _BOOL_WORDS:
        return (a.lower() in _TRUE_WORDS) is (b.lower() in _TRUE_WORDS)
    x, y = _number(a), _number(b)
    if x is not None and y is not None:
        return math.isclose(x, y)
    return a == b


@expose_substitution('equals')
class EqualsSubstitution(Substitution):
    """'true' when `left` and `right` are equal after substitution, else 'false'.

    'True' and '1' equal each other (booleans in any case), '2.0' equals '2' (numbers, within float
    rounding); anything else must be the same text.
    """

    def __init__(self, left: Any | Iterable[Any] | None, right: Any | Iterable[Any] | None) -> None:
        super().__init__()
        self._sides = (_operand(left), _operand(right))

    @property
    def left(self) -> list[Substitution]:
        return self._sides[0]

    @property
    def right(self) -> list[Substitution]:
        return self._sides[1]

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        # ROS 2 words the count error of `equals` as that of `and`
        return cls, tag_kwargs(data, ('left', 'right'), 'and substitution expects 2 arguments')

    def _equal(self, context: LaunchContext) -> bool:
        left, right = (perform_substitutions(context, side) for side in self._sides)
        return texts_equal(left, right)

    def describe(self) -> str:
        return f'EqualsSubstitution({self.left} {self.right})'

    def perform(self, context: LaunchContext) -> str:
        return bool_text(self._equal(context))
