"""Logic on booleans held as text: `$(not x)`, `$(and a b)`, `$(or a b)`, `$(any …)`, `$(all …)`.

Every operand is read the way typed substitutions read a `bool` ('true'/'false', '1'/'0', YAML's other
spellings); text that is none of them makes the substitution fail. All operands are read before the
result is combined, so a bad operand fails even where it would not change the answer.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, ClassVar

from .._private.operands import bool_text, tag_kwargs, truth_of
from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


class _Logic(Substitution):
    """Reads each operand as a boolean and folds them with `combine`."""

    combine: ClassVar[Callable[[list[bool]], bool]]

    def __init__(self, *operands: SomeSubstitutionsType) -> None:
        super().__init__()
        self._operands = [normalize_to_list_of_substitutions(operand) for operand in operands]

    def perform(self, context: LaunchContext) -> str:
        readings = [truth_of(context, operand) for operand in self._operands]
        return bool_text(type(self).combine(readings))


@expose_substitution('not')
class NotSubstitution(_Logic):
    """'true' for a false `value`, 'false' for a true one."""

    combine = staticmethod(lambda readings: not readings[0])

    def __init__(self, value: SomeSubstitutionsType) -> None:
        super().__init__(value)

    @property
    def value(self) -> list[Substitution]:
        return self._operands[0]

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        return cls, tag_kwargs(data, ('value',), 'not substitution expects 1 argument')

    def describe(self) -> str:
        return f'NotSubstitution({self.value})'


class _Pair(_Logic):
    """An operator between a `left` and a `right` operand."""

    def __init__(self, left: SomeSubstitutionsType, right: SomeSubstitutionsType) -> None:
        super().__init__(left, right)

    @property
    def left(self) -> list[Substitution]:
        return self._operands[0]

    @property
    def right(self) -> list[Substitution]:
        return self._operands[1]

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        # `or` reports its arity under `and`'s name, as ROS 2 does
        return cls, tag_kwargs(data, ('left', 'right'), 'and substitution expects 2 arguments')

    def describe(self) -> str:
        # `or` describes itself as an AndSubstitution too, as ROS 2's does
        return f'AndSubstitution({self.left} {self.right})'


@expose_substitution('and')
class AndSubstitution(_Pair):
    """'true' when `left` and `right` are both true."""

    combine = staticmethod(all)


@expose_substitution('or')
class OrSubstitution(_Pair):
    """'true' when `left` or `right` (or both) is true."""

    combine = staticmethod(any)


class _Variadic(_Logic):
    """An operator over any number of operands, given positionally."""

    def __init__(self, *args: SomeSubstitutionsType) -> None:
        super().__init__(*args)

    @property
    def args(self) -> list[list[Substitution]]:
        return self._operands

    @classmethod
    def parse(cls, data: Iterable[SomeSubstitutionsType]):
        # the parser calls back with keywords only, the constructor takes the operands positionally
        def make(*, args: Iterable[SomeSubstitutionsType]) -> _Variadic:
            return cls(*args)

        return make, {'args': data}

    def describe(self) -> str:
        listed = ' '.join(str(operand) for operand in self._operands)
        return f'{type(self).__name__}({listed})'


@expose_substitution('any')
class AnySubstitution(_Variadic):
    """'true' when one operand or more is true ('false' without operands)."""

    combine = staticmethod(any)


@expose_substitution('all')
class AllSubstitution(_Variadic):
    """'true' when no operand is false ('true' without operands)."""

    combine = staticmethod(all)
