"""Type aliases of node parameters at each stage: as a launch file gives them (`Some*`), normalized to
substitutions (`Parameters`), and evaluated (`EvaluatedParameters`)."""

import pathlib
from collections.abc import Mapping, Sequence
from typing import Any

from diffctl.launch.some_substitutions_type import SomeSubstitutionsType, SomeSubstitutionsType_types_tuple
from diffctl.launch.substitution import Substitution

from .parameter_descriptions import Parameter as ParameterDescription
from .parameter_descriptions import ParameterFile
from .parameter_descriptions import ParameterValue as ParameterValueDescription

_SingleValueType_types_tuple = (str, int, float, bool)
_SingleValueType = str | int | float | bool
_MultiValueType = Sequence[str] | Sequence[int] | Sequence[float] | Sequence[bool] | bytes

SomeParameterFile = SomeSubstitutionsType | pathlib.Path | ParameterFile
SomeParameterName = Sequence[Substitution | str]
SomeParameterValue = (
    ParameterValueDescription
    | SomeSubstitutionsType
    | Sequence[SomeSubstitutionsType]
    | _SingleValueType
    | _MultiValueType
)
SomeParameterValue_types_tuple = (*SomeSubstitutionsType_types_tuple, *_SingleValueType_types_tuple, bytes)

# Nested dictionaries: a value may itself be a dictionary of the same kind (mypy has no recursive aliases here).
SomeParametersDict = Mapping[SomeParameterName, SomeParameterValue | Mapping[SomeParameterName, Any]]
SomeParameters = Sequence[SomeParameterFile | ParameterDescription | SomeParametersDict]

ParameterName = Sequence[Substitution]
ParameterValue = (
    Sequence[Substitution]
    | Sequence[Sequence[Substitution]]
    | _SingleValueType
    | _MultiValueType
    | ParameterValueDescription
)
ParametersDict = dict[ParameterName, ParameterValue]  # flat: nested names joined with '.'
Parameters = Sequence[ParameterFile | ParametersDict | ParameterDescription]

EvaluatedParameterValue = _SingleValueType | _MultiValueType
EvaluatedParameters = Sequence[pathlib.Path | ParameterDescription | dict[str, EvaluatedParameterValue]]

__all__ = [
    "EvaluatedParameterValue",
    "EvaluatedParameters",
    "ParameterFile",
    "ParameterName",
    "ParameterValue",
    "Parameters",
    "ParametersDict",
    "SomeParameterFile",
    "SomeParameterName",
    "SomeParameterValue",
    "SomeParameterValue_types_tuple",
    "SomeParameters",
    "SomeParametersDict",
]
