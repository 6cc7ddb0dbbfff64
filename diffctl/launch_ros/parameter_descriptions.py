"""Descriptions of node parameters: ParameterValue (a value and the type it is coerced to), Parameter (a
name and a value, passed as `-p name:=value`) and ParameterFile (a YAML file, optionally with substitutions)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

from diffctl.launch.frontend.parse_substitution import parse_substitution
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType, SomeSubstitutionsType_types_tuple
from diffctl.launch.substitution import Substitution
from diffctl.launch.substitutions import SubstitutionFailure
from diffctl.launch.utilities import ensure_argument_type, normalize_to_list_of_substitutions, perform_substitutions
from diffctl.launch.utilities.type_utils import (
    AllowedTypesType,
    SomeValueType,
    coerce_to_type,
    is_normalized_substitution,
    normalize_typed_substitution,
    perform_typed_substitution,
)

if TYPE_CHECKING:
    from .parameters_type import EvaluatedParameterValue

_UNSET: Any = object()


class ParameterValue:
    """A parameter's value, possibly made of substitutions, and the type it must have once evaluated.

    `value_type` is one of int, float, bool, str, List[int], List[float], List[bool], List[str], or None for
    YAML's rules (whose result must then be one of those). A value given without substitutions is checked
    against `value_type` at once (TypeError).
    """

    def __init__(self, value: SomeValueType, *, value_type: AllowedTypesType | None = None) -> None:
        self.__value = normalize_typed_substitution(value, value_type)
        self.__value_type = value_type
        self.__evaluated: Any = _UNSET

    @property
    def value(self) -> Any:
        """The evaluated value once `evaluate` ran, the (normalized) given value before."""
        return self.__value if self.__evaluated is _UNSET else self.__evaluated

    @property
    def value_type(self) -> AllowedTypesType | None:
        return self.__value_type

    def __str__(self) -> str:
        return f"launch_ros.description.ParameterValue(value={self.value}, value_type={self.value_type})"

    def evaluate(self, context: LaunchContext) -> EvaluatedParameterValue:
        """Perform the substitutions and coerce the result; later calls give the same value."""
        if self.__evaluated is _UNSET:
            if self.__value_type is None and is_normalized_substitution(self.__value):
                self.__evaluated = _yaml_or_text(perform_substitutions(context, self.__value))
            else:
                self.__evaluated = perform_typed_substitution(context, self.__value, self.__value_type)
        return self.__evaluated


def _yaml_or_text(text: str) -> Any:
    """An untyped value's performed text by YAML's rules, as launch_ros reads it; text that is no YAML at all
    (a robot description read by `let file`, an SDF or URDF) is passed on as the string, where launch_ros
    fails converting it. Valid YAML of a type no parameter has still fails."""
    import yaml

    try:
        yaml.safe_load(text)
    except yaml.YAMLError:
        return text
    return coerce_to_type(text, None)


class Parameter:
    """One named parameter of a node (a Node passes it on its command line as `-p name:=value`)."""

    def __init__(
        self, name: SomeSubstitutionsType, value: SomeValueType, *, value_type: AllowedTypesType | None = None
    ) -> None:
        ensure_argument_type(name, SomeSubstitutionsType_types_tuple, "name")
        self.__name = normalize_to_list_of_substitutions(name)
        self.__parameter_value = ParameterValue(value, value_type=value_type)
        self.__evaluated: tuple[str, Any] | None = None

    @property
    def name(self) -> list[Substitution] | str:
        """The evaluated name once `evaluate` ran, its substitutions before."""
        return self.__name if self.__evaluated is None else self.__evaluated[0]

    @property
    def value(self) -> Any:
        return self.__parameter_value.value

    @property
    def value_type(self) -> AllowedTypesType | None:
        return self.__parameter_value.value_type

    def __str__(self) -> str:
        return (
            f"launch_ros.description.Parameter(name={self.name}, value={self.value}, value_type={self.value_type})"
        )

    def evaluate(self, context: LaunchContext) -> tuple[str, EvaluatedParameterValue]:
        """(name, value) after substitution; evaluated once."""
        if self.__evaluated is None:
            self.__evaluated = (perform_substitutions(context, self.__name), self.__parameter_value.evaluate(context))
        return self.__evaluated


class ParameterFile:
    """A parameters YAML file; with `allow_substs` its `$(...)` are performed into a temporary copy."""

    def __init__(
        self,
        param_file: os.PathLike | bytes | SomeSubstitutionsType,
        *,
        allow_substs: bool | SomeSubstitutionsType = False,
    ) -> None:
        # set first: __del__ runs even when the checks below raise
        self.__evaluated_file: Path | None = None
        self.__temporary = False
        ensure_argument_type(
            param_file, (*SomeSubstitutionsType_types_tuple, os.PathLike, bytes), "param_file", "ParameterFile()"
        )
        ensure_argument_type(
            allow_substs, (bool, *SomeSubstitutionsType_types_tuple), "allow_subst", "ParameterFile()"
        )
        self.__param_file: Any = (
            normalize_to_list_of_substitutions(param_file)
            if isinstance(param_file, SomeSubstitutionsType_types_tuple)
            else param_file
        )
        self.__allow_substs = normalize_typed_substitution(allow_substs, data_type=bool)
        self.__evaluated_allow_substs: bool | None = None

    @property
    def param_file(self) -> Any:
        """The path once evaluated, else what was given (substitutions, or a path-like)."""
        return self.__param_file if self.__evaluated_file is None else self.__evaluated_file

    @property
    def allow_substs(self) -> Any:
        return self.__allow_substs if self.__evaluated_allow_substs is None else self.__evaluated_allow_substs

    def __str__(self) -> str:
        return f"launch_ros.description.ParameterFile(param_file={self.param_file}, allow_substs={self.allow_substs})"

    def evaluate(self, context: LaunchContext) -> Path:
        """The file to hand to the node: the given one, or a substituted copy (SubstitutionFailure when that
        copy is not YAML)."""
        if self.__evaluated_file is not None:
            return self.__evaluated_file
        given = self.__param_file
        path = Path(perform_substitutions(context, given) if isinstance(given, list) else os.fsdecode(given))
        allow = bool(perform_typed_substitution(context, self.__allow_substs, bool))
        self.__evaluated_allow_substs = allow
        if allow:
            import tempfile

            import yaml

            text = perform_substitutions(context, parse_substitution(path.read_text()))
            try:
                yaml.safe_load(text)
            except yaml.YAMLError:
                raise SubstitutionFailure("The substituted parameter file is not a valid yaml file") from None
            with tempfile.NamedTemporaryFile("w", prefix="launch_params_", delete=False) as out:
                out.write(text)
            path = Path(out.name)
            self.__temporary = True
        self.__evaluated_file = path
        return path

    def cleanup(self) -> None:
        """Remove the substituted copy, if one was written (the description can be evaluated again)."""
        if self.__temporary and self.__evaluated_file is not None:
            self.__evaluated_file.unlink(missing_ok=True)
            self.__evaluated_file = None
            self.__temporary = False

    def __del__(self) -> None:
        self.cleanup()
