"""`LaunchConfiguration` (`$(var name [default])`): the value of a launch configuration."""

from __future__ import annotations

import collections.abc
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions
from .substitution_failure import SubstitutionFailure

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_substitution('var')
class LaunchConfiguration(Substitution):
    """The launch configuration `variable_name` (an argument or a `let`).

    When it is not set, `default` is used (items that are neither strings nor substitutions are turned
    into text with `str`); without a default that is a SubstitutionFailure.
    """

    def __init__(self, variable_name: SomeSubstitutionsType, *, default: Any | Iterable[Any] | None = None) -> None:
        super().__init__()
        self.__variable_name = normalize_to_list_of_substitutions(variable_name)
        self.__default: list[Substitution] | None = None
        if default is not None:
            items = default if isinstance(default, collections.abc.Iterable) else (default,)
            self.__default = normalize_to_list_of_substitutions(
                [item if isinstance(item, (str, Substitution)) else str(item) for item in items])

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        if not 1 <= len(data) <= 2:
            raise TypeError('var substitution expects 1 or 2 arguments')
        kwargs = {'variable_name': data[0]}
        if len(data) == 2:
            kwargs['default'] = data[1]
        return cls, kwargs

    @property
    def variable_name(self) -> list[Substitution]:
        return self.__variable_name

    def describe(self) -> str:
        return 'LaunchConfig({})'.format(' + '.join(s.describe() for s in self.variable_name))

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.__variable_name)
        if name in context.launch_configurations:
            return context.launch_configurations[name]
        if self.__default is None:
            raise SubstitutionFailure(f"launch configuration '{name}' does not exist")
        return perform_substitutions(context, self.__default)
