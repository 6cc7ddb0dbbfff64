"""`LaunchConfigurationEquals` (deprecated): true when a launch configuration has a given value."""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING

from ..condition import Condition
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType
    from ..substitution import Substitution


class LaunchConfigurationEquals(Condition):
    """True when the launch configuration equals `expected_value`; with None, when it is not set.

    Deprecated: use `IfCondition(EqualsSubstitution(LaunchConfiguration(name), value))`.
    """

    def __init__(self, launch_configuration_name: str, expected_value: SomeSubstitutionsType | None) -> None:
        warnings.warn(
            "The 'LaunchConfigurationEquals' and 'LaunchConfigurationNotEquals' Conditions are "
            " deprecated. Use the 'EqualsSubstitution' and 'NotEqualsSubstitution' substitutions "
            'instead! E.g.:\n'
            '  IfCondition(\n  '
            "\tEqualsSubstitution(LaunchConfiguration('some_launch_arg'), \"some_equality_check\")"
            '\n  )',
            UserWarning, stacklevel=2)
        self.__launch_configuration_name = launch_configuration_name
        self.__expected_value: list[Substitution] | None = (
            None if expected_value is None else normalize_to_list_of_substitutions(expected_value))
        super().__init__(predicate=self._predicate_func)

    def _predicate_func(self, context: LaunchContext) -> bool:
        expected = None if self.__expected_value is None else perform_substitutions(context, self.__expected_value)
        try:
            return context.launch_configurations[self.__launch_configuration_name] == expected
        except KeyError:
            return expected is None

    def describe(self) -> str:
        return self.__repr__()
