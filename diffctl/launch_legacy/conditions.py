"""Conditions on entities: `if:` / `unless:` in YAML, IfCondition / UnlessCondition in Python."""

from __future__ import annotations

import warnings
from abc import ABC, abstractmethod
from typing import TYPE_CHECKING

from diffctl.errors import LaunchError
from diffctl.launch_legacy.substitutions import SomeSubstitutions, normalize, perform

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope

TRUE_WORDS = ("true", "1")
FALSE_WORDS = ("false", "0")


def truth(text: str, what: str) -> bool:
    """'true'/'1' → True, 'false'/'0' → False (any case, surrounding space ignored), anything else an error."""
    word = text.strip().lower()
    if word in TRUE_WORDS:
        return True
    if word in FALSE_WORDS:
        return False
    raise LaunchError(f"{what}: {text!r} is not a boolean", hint="valid: true, false, 1, 0")


class Condition(ABC):
    @abstractmethod
    def evaluate(self, scope: Scope) -> bool:
        """Whether the guarded entity runs."""

    @abstractmethod
    def describe(self) -> str:
        """How --print shows the condition."""


def _describe(subs: SomeSubstitutions) -> str:
    return "".join(s.describe() for s in normalize(subs))


class IfCondition(Condition):
    def __init__(self, predicate_expression: SomeSubstitutions) -> None:
        self.expression = normalize(predicate_expression)

    def evaluate(self, scope: Scope) -> bool:
        return truth(perform(self.expression, scope), f"if {self.describe_expr()}")

    def describe_expr(self) -> str:
        return _describe(self.expression)

    def describe(self) -> str:
        return f"if {self.describe_expr()}"


class UnlessCondition(IfCondition):
    def evaluate(self, scope: Scope) -> bool:
        return not truth(perform(self.expression, scope), f"unless {self.describe_expr()}")

    def describe(self) -> str:
        return f"unless {self.describe_expr()}"


class LaunchConfigurationEquals(Condition):
    def __init__(self, launch_configuration_name: str, expected_value: SomeSubstitutions | None) -> None:
        # launch's own deprecation warning, word for word (both conditions print it, once per process)
        warnings.warn(
            "The 'LaunchConfigurationEquals' and 'LaunchConfigurationNotEquals' Conditions are "
            " deprecated. Use the 'EqualsSubstitution' and 'NotEqualsSubstitution' substitutions "
            "instead! E.g.:\n"
            "  IfCondition(\n  "
            "\tEqualsSubstitution(LaunchConfiguration('some_launch_arg'), \"some_equality_check\")"
            "\n  )",
            UserWarning,
            stacklevel=1,
        )
        self.name = launch_configuration_name
        self.expected = None if expected_value is None else normalize(expected_value)

    def evaluate(self, scope: Scope) -> bool:
        value = scope.configurations.get(self.name)
        expected = None if self.expected is None else perform(self.expected, scope)
        return value == expected

    def describe(self) -> str:
        return f"$(var {self.name}) == {_describe(self.expected) if self.expected is not None else 'unset'}"


class LaunchConfigurationNotEquals(LaunchConfigurationEquals):
    def evaluate(self, scope: Scope) -> bool:
        return not super().evaluate(scope)

    def describe(self) -> str:
        return super().describe().replace(" == ", " != ")
