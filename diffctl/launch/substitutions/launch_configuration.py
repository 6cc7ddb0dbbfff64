"""`LaunchConfiguration`, `$(var name [default])`: an argument's or a `let`'s value."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

from .._private.operands import joined, tag_kwargs
from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions
from .substitution_failure import SubstitutionFailure

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


def _default_parts(default: Any | Iterable[Any]) -> list[Substitution]:
    """A default of any values: strings and substitutions stay, numbers and the like become their text."""
    pieces = default if isinstance(default, Iterable) else [default]
    return normalize_to_list_of_substitutions(
        [piece if isinstance(piece, (str, Substitution)) else str(piece) for piece in pieces])


@expose_substitution('var')
class LaunchConfiguration(Substitution):
    """The launch configuration called `variable_name`, or `default` while there is none (else a failure)."""

    def __init__(self, variable_name: SomeSubstitutionsType, *, default: Any | Iterable[Any] | None = None) -> None:
        super().__init__()
        self._key = normalize_to_list_of_substitutions(variable_name)
        self._fallback = None if default is None else _default_parts(default)

    @property
    def variable_name(self) -> list[Substitution]:
        return self._key

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        kwargs = tag_kwargs(data, ('variable_name', 'default'), 'var substitution expects 1 or 2 arguments', required=1)
        return cls, kwargs

    def describe(self) -> str:
        return f'LaunchConfig({joined(self._key)})'

    def perform(self, context: LaunchContext) -> str:
        key = perform_substitutions(context, self._key)
        configurations = context.launch_configurations
        if key in configurations:
            return configurations[key]
        if self._fallback is not None:
            return perform_substitutions(context, self._fallback)
        raise SubstitutionFailure(f"launch configuration '{key}' does not exist")
