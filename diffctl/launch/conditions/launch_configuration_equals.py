"""`LaunchConfigurationEquals` (deprecated): an action runs when a launch configuration has a value."""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING

from ..condition import Condition
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType

# the deprecation notice ROS 2 users know, word for word
_DEPRECATED = (
    "The 'LaunchConfigurationEquals' and 'LaunchConfigurationNotEquals' Conditions are  deprecated. Use the "
    "'EqualsSubstitution' and 'NotEqualsSubstitution' substitutions instead! E.g.:\n  IfCondition(\n  \t"
    "EqualsSubstitution(LaunchConfiguration('some_launch_arg'), \"some_equality_check\")\n  )"
)


class LaunchConfigurationEquals(Condition):
    """Holds when the launch configuration is set to `expected_value` (unset, when that is None).

    Deprecated in favour of `IfCondition(EqualsSubstitution(LaunchConfiguration(name), value))`.
    """

    _holds_when = True  # LaunchConfigurationNotEquals flips it

    def __init__(self, launch_configuration_name: str, expected_value: SomeSubstitutionsType | None) -> None:
        warnings.warn(_DEPRECATED, UserWarning, stacklevel=2)
        self._name = launch_configuration_name
        self._wanted = None if expected_value is None else normalize_to_list_of_substitutions(expected_value)
        super().__init__(predicate=self._check)

    def _check(self, context: LaunchContext) -> bool:
        wanted = None if self._wanted is None else perform_substitutions(context, self._wanted)
        actual = context.launch_configurations.get(self._name)
        return (actual == wanted) is self._holds_when
