"""`LaunchConfigurationNotEquals` (deprecated): an action runs unless a configuration has a value."""

from __future__ import annotations

from .launch_configuration_equals import LaunchConfigurationEquals


class LaunchConfigurationNotEquals(LaunchConfigurationEquals):
    """Holds when the launch configuration differs from `expected_value` (is set, when that is None).

    Deprecated in favour of `IfCondition(NotEqualsSubstitution(LaunchConfiguration(name), value))`.
    """

    _holds_when = False
