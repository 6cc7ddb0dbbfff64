"""Node parameters as a launch file gives them → substitutions and plain values, checked as early as possible.

Files (paths, substitutions) become ParameterFile; dictionaries are flattened (`{'a': {'b': 1}}` → `a.b`),
their names become tuples of substitutions and their values one of: a plain value (int, float, bool, bytes),
a tuple of substitutions (one string, read as YAML when evaluated — a plain `str` is written as YAML here, so
it stays a string), a tuple of uniform plain values, a tuple of tuples of substitutions (a list of strings,
each read as YAML), or a ParameterValue.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from diffctl.launch.some_substitutions_type import SomeSubstitutionsType_types_tuple
from diffctl.launch.substitution import Substitution
from diffctl.launch.substitutions import TextSubstitution
from diffctl.launch.utilities import ensure_argument_type, normalize_to_list_of_substitutions

from ..parameter_descriptions import Parameter as ParameterDescription
from ..parameter_descriptions import ParameterFile
from ..parameter_descriptions import ParameterValue as ParameterValueDescription
from ..parameters_type import Parameters, ParametersDict, ParameterValue, SomeParameters, SomeParametersDict


def _kind(item: Any) -> type:
    """The category an item of a list parameter falls in (bool before int: a bool is an int too)."""
    for kind in (Substitution, str, bool, int, float):
        if isinstance(item, kind):
            return kind
    if isinstance(item, Sequence):
        return tuple
    raise RuntimeError(f"Failed to handle type {item!r}")


def _normalize_parameter_array_value(value: Any) -> ParameterValue:
    """A list value: uniform numbers or bools stay values; substitutions (with text) join into one string;
    anything else is a list of strings, each element kept as substitutions (plain items written as YAML)."""
    if not isinstance(value, Sequence):
        raise TypeError(f"Value {value!r} must be a sequence")
    allowed = (float, int, str, bool, *SomeSubstitutionsType_types_tuple)
    for item in value:
        ensure_argument_type(item, allowed, "subvalue")
    kinds = {_kind(item) for item in value}
    if kinds == {int}:
        return tuple(int(v) for v in value)
    if kinds and kinds <= {int, float}:
        return tuple(float(v) for v in value)
    if kinds == {bool}:
        return tuple(bool(v) for v in value)
    if Substitution in kinds and kinds <= {str, Substitution}:
        return tuple(normalize_to_list_of_substitutions(value))
    import yaml

    return tuple(
        normalize_to_list_of_substitutions(yaml.dump(v) if isinstance(v, (float, int, bool, str)) else v)
        for v in value
    )


def _normalize_value(value: Any) -> ParameterValue:
    if isinstance(value, ParameterValueDescription):
        return value
    if isinstance(value, str):
        import yaml  # a launch without such parameters never imports it

        return tuple(normalize_to_list_of_substitutions(yaml.dump(value)))
    if isinstance(value, Substitution):
        return (value,)
    if isinstance(value, (float, bool, int, bytes)):
        return value
    if isinstance(value, Sequence):
        return _normalize_parameter_array_value(value)
    raise TypeError(f"Unexpected type for parameter value {value!r}")


def normalize_parameter_dict(
    parameters: SomeParametersDict, *, _prefix: Sequence[Substitution] | None = None
) -> ParametersDict:
    """A dictionary of parameters, flattened, names as tuples of substitutions (TypeError on what a node
    parameter cannot be: nested lists, sets, objects, keys that are not text)."""
    if not isinstance(parameters, Mapping):
        raise TypeError("expected dict")
    out: ParametersDict = {}
    for key, value in parameters.items():
        name = normalize_to_list_of_substitutions(key)
        if _prefix:
            name = [*_prefix, TextSubstitution(text="."), *name]
        if isinstance(value, Mapping):
            out.update(normalize_parameter_dict(value, _prefix=name))
        else:
            out[tuple(name)] = _normalize_value(value)
    return out


def normalize_parameters(parameters: SomeParameters) -> Parameters:
    """A node's `parameters` list: dictionaries normalized, descriptions kept, anything else a file."""
    if isinstance(parameters, str) or not isinstance(parameters, Sequence):
        raise TypeError(f"Expecting list of parameters, got {parameters}")
    out: list[Any] = []
    for entry in parameters:
        if isinstance(entry, Mapping):
            out.append(normalize_parameter_dict(entry))
        elif isinstance(entry, (ParameterDescription, ParameterFile)):
            out.append(entry)
        else:
            out.append(ParameterFile(entry))
    return tuple(out)
