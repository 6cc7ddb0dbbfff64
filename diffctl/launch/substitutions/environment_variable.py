"""`EnvironmentVariable`, `$(env NAME [default])`: a variable of the launch's environment."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from .._private.operands import joined, tag_kwargs
from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions
from .substitution_failure import SubstitutionFailure

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_substitution('env')
class EnvironmentVariable(Substitution):
    """The value of `name` in `context.environment`, else `default_value`, else a failure."""

    def __init__(self, name: SomeSubstitutionsType, *, default_value: SomeSubstitutionsType | None = None) -> None:
        super().__init__()
        self._variable = normalize_to_list_of_substitutions(name)
        self._fallback = None if default_value is None else normalize_to_list_of_substitutions(default_value)

    @property
    def name(self) -> list[Substitution]:
        return self._variable

    @property
    def default_value(self) -> list[Substitution] | None:
        return self._fallback

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        kwargs = tag_kwargs(
            data, ('name', 'default_value'), 'env substitution expects 1 or 2 arguments', required=1)
        return cls, kwargs

    def describe(self) -> str:
        return f'EnvVar({joined(self._variable)})'

    def perform(self, context: LaunchContext) -> str:
        # the default is performed even when unused: its own failures show either way
        fallback = None if self._fallback is None else perform_substitutions(context, self._fallback)
        variable = perform_substitutions(context, self._variable)
        found = context.environment.get(variable, fallback)
        if found is None:
            raise SubstitutionFailure(f"environment variable '{variable}' does not exist")
        return found
