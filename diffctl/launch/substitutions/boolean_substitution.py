"""Boolean substitutions: `$(not x)`, `$(and a b)`, `$(or a b)`, `$(any …)`, `$(all …)` → 'true' / 'false'.

Operands are read as booleans with the typed-substitution rules ('true', 'false', '1', '0', YAML's
spellings); anything else is a SubstitutionFailure.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING

from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.type_utils import perform_typed_substitution
from .substitution_failure import SubstitutionFailure

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


def _truth(context: LaunchContext, value: list[Substitution]) -> bool:
    try:
        return perform_typed_substitution(context, value, bool)
    except (TypeError, ValueError) as e:
        raise SubstitutionFailure(e) from e


def _text(value: bool) -> str:
    return 'true' if value else 'false'


@expose_substitution('not')
class NotSubstitution(Substitution):
    """'true' when `value` is false, and the other way round."""

    def __init__(self, value: SomeSubstitutionsType) -> None:
        super().__init__()
        self.__value = normalize_to_list_of_substitutions(value)

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        if len(data) != 1:
            raise TypeError('not substitution expects 1 argument')
        return cls, {'value': data[0]}

    @property
    def value(self) -> list[Substitution]:
        return self.__value

    def describe(self) -> str:
        return f'NotSubstitution({self.value})'

    def perform(self, context: LaunchContext) -> str:
        return _text(not _truth(context, self.value))


class _Binary(Substitution):
    """A boolean operator of two operands."""

    def __init__(self, left: SomeSubstitutionsType, right: SomeSubstitutionsType) -> None:
        super().__init__()
        self.__left = normalize_to_list_of_substitutions(left)
        self.__right = normalize_to_list_of_substitutions(right)

    @property
    def left(self) -> list[Substitution]:
        return self.__left

    @property
    def right(self) -> list[Substitution]:
        return self.__right

    def describe(self) -> str:
        # upstream describes `or` as AndSubstitution too
        return f'AndSubstitution({self.left} {self.right})'


@expose_substitution('and')
class AndSubstitution(_Binary):
    """'true' when both operands are true."""

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        if len(data) != 2:
            raise TypeError('and substitution expects 2 arguments')
        return cls, {'left': data[0], 'right': data[1]}

    def perform(self, context: LaunchContext) -> str:
        left = _truth(context, self.left)
        right = _truth(context, self.right)
        return _text(left and right)


@expose_substitution('or')
class OrSubstitution(_Binary):
    """'true' when either operand is true."""

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        if len(data) != 2:
            raise TypeError('and substitution expects 2 arguments')
        return cls, {'left': data[0], 'right': data[1]}

    def perform(self, context: LaunchContext) -> str:
        left = _truth(context, self.left)
        right = _truth(context, self.right)
        return _text(left or right)


class _Many(Substitution):
    """A boolean operator of any number of operands."""

    def __init__(self, *args: SomeSubstitutionsType) -> None:
        super().__init__()
        self.__args = [normalize_to_list_of_substitutions(arg) for arg in args]

    @classmethod
    def parse(cls, data: Iterable[SomeSubstitutionsType]):
        # the operands are positional: build through a function taking them as `args`
        def build(*, args: Iterable[SomeSubstitutionsType]) -> _Many:
            return cls(*args)

        return build, {'args': data}

    @property
    def args(self) -> list[list[Substitution]]:
        return self.__args

    def describe(self) -> str:
        return f'{type(self).__name__}({" ".join(str(arg) for arg in self.args)})'

    def _values(self, context: LaunchContext) -> list[bool]:
        return [_truth(context, arg) for arg in self.args]


@expose_substitution('any')
class AnySubstitution(_Many):
    """'true' when at least one operand is true."""

    def perform(self, context: LaunchContext) -> str:
        return _text(any(self._values(context)))


@expose_substitution('all')
class AllSubstitution(_Many):
    """'true' when every operand is true."""

    def perform(self, context: LaunchContext) -> str:
        return _text(all(self._values(context)))
