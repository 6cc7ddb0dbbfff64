"""`EqualsSubstitution` (`$(equals a b)`): 'true' when two values are equal."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.type_utils import is_substitution, perform_substitutions

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


def _as_text(value: Any) -> Any:
    if is_substitution(value):
        return value
    if value is None:
        return ''
    if isinstance(value, bool):
        return 'true' if value else 'false'
    return str(value)


def _is_bool_text(text: str) -> bool:
    return isinstance(text, str) and text.lower() in ('true', 'false', '1', '0')


def _is_float_text(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


@expose_substitution('equals')
class EqualsSubstitution(Substitution):
    """'true' or 'false': whether `left` equals `right` once performed.

    Plain values are compared as text (None as '', booleans as 'true'/'false'); two boolean texts
    ('true', 'false', '1', '0', any case) compare as booleans, two numbers as floats (close enough).
    """

    def __init__(self, left: Any | Iterable[Any] | None, right: Any | Iterable[Any] | None) -> None:
        super().__init__()
        self.__left = normalize_to_list_of_substitutions(_as_text(left))
        self.__right = normalize_to_list_of_substitutions(_as_text(right))

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        if len(data) != 2:
            raise TypeError('and substitution expects 2 arguments')
        return cls, {'left': data[0], 'right': data[1]}

    @property
    def left(self) -> list[Substitution]:
        return self.__left

    @property
    def right(self) -> list[Substitution]:
        return self.__right

    def describe(self) -> str:
        return f'EqualsSubstitution({self.left} {self.right})'

    def perform(self, context: LaunchContext) -> str:
        left = perform_substitutions(context, self.left)
        right = perform_substitutions(context, self.right)
        if _is_bool_text(left) and _is_bool_text(right):
            equal = (left.lower() in ('true', '1')) == (right.lower() in ('true', '1'))
        elif _is_float_text(left) and _is_float_text(right):
            equal = math.isclose(float(left), float(right))
        else:
            equal = left == right
        return 'true' if equal else 'false'
