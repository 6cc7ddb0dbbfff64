"""`LaunchConfigurationNotEquals` (deprecated): true when a launch configuration differs from a value."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .launch_configuration_equals import LaunchConfigurationEquals

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


class LaunchConfigurationNotEquals(LaunchConfigurationEquals):
    """The negation of `LaunchConfigurationEquals`; with None, true when the configuration is set.

    Deprecated: use `IfCondition(NotEqualsSubstitution(LaunchConfiguration(name), value))`.
    """

    def __init__(self, launch_configuration_name: str, expected_value: SomeSubstitutionsType | None) -> None:
        super().__init__(launch_configuration_name, expected_value)

    def _predicate_func(self, context: LaunchContext) -> bool:
        return not super()._predicate_func(context)

    def describe(self) -> str:
        return self.__repr__()
