"""`EnvironmentVariable` (`$(env NAME [default])`): the value of an environment variable."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

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
    """The variable `name` of the launch's environment (`context.environment`).

    When it is not set, `default_value` is used; without one that is a SubstitutionFailure.
    """

    def __init__(self, name: SomeSubstitutionsType, *, default_value: SomeSubstitutionsType | None = None) -> None:
        super().__init__()
        self.__name = normalize_to_list_of_substitutions(name)
        self.__default_value = None if default_value is None else normalize_to_list_of_substitutions(default_value)

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        if not 1 <= len(data) <= 2:
            raise TypeError('env substitution expects 1 or 2 arguments')
        kwargs = {'name': data[0]}
        if len(data) == 2:
            kwargs['default_value'] = data[1]
        return cls, kwargs

    @property
    def name(self) -> list[Substitution]:
        return self.__name

    @property
    def default_value(self) -> list[Substitution] | None:
        return self.__default_value

    def describe(self) -> str:
        return 'EnvVar({})'.format(' + '.join(sub.describe() for sub in self.name))

    def perform(self, context: LaunchContext) -> str:
        default = None if self.default_value is None else perform_substitutions(context, self.default_value)
        name = perform_substitutions(context, self.name)
        value = context.environment.get(name, default)
        if value is None:
            raise SubstitutionFailure(f"environment variable '{name}' does not exist")
        return value
