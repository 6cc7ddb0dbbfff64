"""Normalized node parameters → values: substitutions performed, text read as YAML, types checked."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.substitution import Substitution
from diffctl.launch.utilities import ensure_argument_type, perform_substitutions

from ..parameter_descriptions import Parameter as ParameterDescription
from ..parameter_descriptions import ParameterFile
from ..parameter_descriptions import ParameterValue as ParameterValueDescription
from ..parameters_type import EvaluatedParameters, EvaluatedParameterValue, Parameters, ParametersDict

_SCALARS = (bool, int, float, str)
_AS_STRING_HINT = (
    "If the parameter is meant to be a string, try wrapping it in "
    "launch_ros.parameter_descriptions.ParameterValue(value, value_type=str)"
)


def _uniform(items: Sequence[Any]) -> bool:
    """A non-empty list whose items all have the first one's type, one of bool, int, float, str."""
    if not items or type(items[0]) not in _SCALARS:
        return False
    return all(isinstance(item, type(items[0])) for item in items)


def _not_uniform(name: str) -> TypeError:
    return TypeError(
        "Expected a non-empty sequence, with items of uniform type. Allowed sequence item types are bool, int, "
        f'float, str. Got inconsistent input for "{name}"'
    )


def _from_text(name: str, text: str) -> EvaluatedParameterValue:
    """One substituted string, read as YAML: a scalar, or a uniform list (as a tuple)."""
    import yaml

    try:
        value = yaml.safe_load(text if text else "''")  # YAML reads '' as null: keep the empty string
    except yaml.YAMLError:
        raise TypeError(f"Unable to parse the value of parameter {name} as yaml. {_AS_STRING_HINT}") from None
    if type(value) in (*_SCALARS, bytes):
        return value
    if isinstance(value, Sequence):
        if not _uniform(value):
            raise _not_uniform(name)
        return tuple(value)
    raise TypeError(
        "Allowed value types are bytes, bool, int, float, str, Sequence[bool], Sequence[int], Sequence[float], "
        f'Sequence[str]. Got {type(value)} for "{name}". {_AS_STRING_HINT}'
    )


def evaluate_parameter_dict(context: LaunchContext, parameters: ParametersDict) -> dict[str, EvaluatedParameterValue]:
    """A normalized parameter dictionary with its names and values evaluated."""
    if not isinstance(parameters, Mapping):
        raise TypeError("expected dict")
    out: dict[str, EvaluatedParameterValue] = {}
    for key, value in parameters.items():
        if not isinstance(key, tuple):
            raise TypeError(f"Expecting tuple of substitutions got {key!r}")
        name = perform_substitutions(context, list(key))
        if isinstance(value, ParameterValueDescription):
            out[name] = value.evaluate(context)
        elif isinstance(value, tuple) and value and isinstance(value[0], Substitution):
            out[name] = _from_text(name, perform_substitutions(context, list(value)))
        elif isinstance(value, tuple) and value and isinstance(value[0], Sequence) and not isinstance(value[0], str):
            import yaml

            items = [yaml.safe_load(perform_substitutions(context, list(item))) for item in value]
            if not _uniform(items):
                raise _not_uniform(name)
            out[name] = tuple(items)
        elif isinstance(value, tuple) and value:
            out[name] = tuple(type(value[0])(item) for item in value)
        else:
            ensure_argument_type(value, (float, int, str, bool, bytes), "value")
            out[name] = value
    return out


def evaluate_parameters(context: LaunchContext, parameters: Parameters) -> EvaluatedParameters:
    """Normalized parameters (see normalize_parameters) → file paths, Parameter descriptions (kept for the
    node's command line) and dictionaries of values."""
    out: list[Any] = []
    for entry in parameters:
        if isinstance(entry, ParameterFile):
            out.append(entry.evaluate(context))
        elif isinstance(entry, ParameterDescription):
            out.append(entry)
        elif isinstance(entry, Mapping):
            out.append(evaluate_parameter_dict(context, entry))
    return tuple(out)
