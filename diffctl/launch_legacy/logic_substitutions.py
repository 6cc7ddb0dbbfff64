"""Boolean and comparison substitutions: `$(not)`, `$(and)`, `$(or)`, `$(any)`, `$(all)`, `$(equals)`, `$(if)`.

Inputs follow launch's rules: booleans as YAML 1.1 words plus 1/0; equality compares booleans as booleans
and numbers within `math.isclose`, anything else as text. Results are the texts `true` / `false`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from diffctl.errors import LaunchError
from diffctl.launch_legacy.substitutions import SomeSubstitutions, Substitution, describe, normalize, perform

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope


class EqualsSubstitution(Substitution):
    def __init__(self, left: SomeSubstitutions, right: SomeSubstitutions) -> None:
        self.left, self.right = normalize(left), normalize(right)

    def describe(self) -> str:
        return f"$(equals {describe(self.left)} {describe(self.right)})"

    def perform(self, scope: Scope) -> str:
        return str(_equal(perform(self.left, scope), perform(self.right, scope))).lower()


class NotSubstitution(Substitution):
    def __init__(self, value: SomeSubstitutions) -> None:
        self.value = normalize(value)

    def describe(self) -> str:
        return f"$(not {describe(self.value)})"

    def perform(self, scope: Scope) -> str:
        return str(not _bool(perform(self.value, scope), "$(not)")).lower()


def _bool(text: str, what: str) -> bool:
    """launch's rule for boolean inputs of substitutions: YAML 1.1 booleans, plus 1 and 0."""
    word = text.strip().lower()
    if word in ("true", "1", "yes", "on", "y"):
        return True
    if word in ("false", "0", "no", "off", "n"):
        return False
    raise LaunchError(f"{what}: {text!r} is not a boolean", hint="valid: true, false, 1, 0")


class NotEqualsSubstitution(Substitution):
    def __init__(self, left: SomeSubstitutions, right: SomeSubstitutions) -> None:
        self.left, self.right = normalize(left), normalize(right)

    def describe(self) -> str:
        return f"$(not-equals {describe(self.left)} {describe(self.right)})"

    def perform(self, scope: Scope) -> str:
        return str(not _equal(perform(self.left, scope), perform(self.right, scope))).lower()


def _equal(a: str, b: str) -> bool:
    """launch's EqualsSubstitution: booleans as booleans, numbers within isclose, anything else as text."""
    try:
        return _bool(a, "") == _bool(b, "")
    except LaunchError:
        pass
    try:
        return math.isclose(float(a), float(b))
    except ValueError:
        return a == b


class _Logic(Substitution):
    """and / or / any / all over boolean texts."""

    word = ""

    def __init__(self, *values: SomeSubstitutions) -> None:
        self.values = [normalize(v) for v in values]

    def describe(self) -> str:
        return f"$({self.word} " + " ".join(describe(v) for v in self.values) + ")"

    def perform(self, scope: Scope) -> str:
        bits = [_bool(perform(v, scope), f"$({self.word})") for v in self.values]
        return str(all(bits) if self.word in ("and", "all") else any(bits)).lower()


class AndSubstitution(_Logic):
    word = "and"

    def __init__(self, left: SomeSubstitutions, right: SomeSubstitutions) -> None:
        super().__init__(left, right)


class OrSubstitution(_Logic):
    word = "or"

    def __init__(self, left: SomeSubstitutions, right: SomeSubstitutions) -> None:
        super().__init__(left, right)


class AllSubstitution(_Logic):
    word = "all"


class AnySubstitution(_Logic):
    word = "any"


class IfElseSubstitution(Substitution):
    """`$(if cond then [else])`."""

    def __init__(
        self, condition: SomeSubstitutions, if_value: SomeSubstitutions = "", else_value: SomeSubstitutions = ""
    ) -> None:
        self.condition = normalize(condition)
        self.if_value, self.else_value = normalize(if_value), normalize(else_value)

    def describe(self) -> str:
        return f"$(if {describe(self.condition)} {describe(self.if_value)} {describe(self.else_value)})"

    def perform(self, scope: Scope) -> str:
        chosen = self.if_value if _bool(perform(self.condition, scope), "$(if)") else self.else_value
        return perform(chosen, scope)


class BooleanSubstitution(Substitution):
    """A value read as a boolean (YAML words, 1/0), given back as `true` / `false` (launch's BooleanSubstitution)."""

    def __init__(self, value: SomeSubstitutions) -> None:
        self.value = normalize(value)

    def describe(self) -> str:
        return f"$(bool {describe(self.value)})"

    def perform(self, scope: Scope) -> str:
        return str(_bool(perform(self.value, scope), "BooleanSubstitution")).lower()
