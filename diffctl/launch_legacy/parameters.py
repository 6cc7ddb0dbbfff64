"""Node parameters in launch files: ParameterValue, Parameter, ParameterFile, and how values get their ROS types.

Python (`parameters=[{...}, "file.yaml", ParameterFile(...)]`), YAML (`param:`) and XML (`<param>`) all end
here: values with substitutions are typed after they are resolved, as launch_ros does. The XML frontend's
text attributes are typed by `coerce` (launch's type_utils rules: `type="str|bool|int|float|list_of_*|yaml"`,
`value-sep`; without a type, YAML decides and must give a scalar or a uniform list).
"""

from __future__ import annotations

import tempfile
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import yaml

from diffctl.errors import LaunchError
from diffctl.launch_legacy.substitutions import SomeSubstitutions, Substitution, normalize, parse, perform

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope

SCALAR_TYPES = ("str", "bool", "int", "float")
TYPES = (*SCALAR_TYPES, *(f"list_of_{t}" for t in SCALAR_TYPES), "yaml")


def _yaml_bool(text: str) -> bool:
    word = text.strip()
    if word in ("1", "0"):
        return word == "1"
    value = yaml.safe_load(word) if word else None
    if isinstance(value, bool):
        return value
    raise ValueError(text)


_SCALAR = {"str": str, "int": int, "float": float, "bool": _yaml_bool}


def _uniform(values: list[Any], text: str) -> list[Any]:
    kinds = {type(v) for v in values}
    if kinds <= {int, float} and float in kinds:
        return [float(v) for v in values]
    if len(kinds) > 1:
        raise LaunchError(f"{text!r} is a non-uniform list", hint="all items of a list parameter have one type")
    return values


def _guess(text: str) -> Any:
    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError:
        return text
    if value is None:
        return text
    if isinstance(value, (bool, int, float, str)):
        return value
    if isinstance(value, list) and all(isinstance(v, (bool, int, float, str)) for v in value):
        return _uniform(value, text)
    raise LaunchError(
        f"{text!r} is neither a scalar nor a list", hint='give type="str" to keep it as text (e.g. a URDF)'
    )


def coerce(text: str, type_name: str | None = None, sep: str | None = None) -> Any:
    """A text attribute → its parameter value, by launch's rules (raises LaunchError naming what is valid)."""
    if type_name is not None and type_name not in TYPES:
        raise LaunchError(f"parameter type {type_name!r} is not valid", hint="valid: " + ", ".join(TYPES))
    if type_name == "yaml":
        try:
            return yaml.safe_load(text)
        except yaml.YAMLError as e:
            raise LaunchError(f"{text!r} is not YAML: {e}") from None
    item_type = type_name[len("list_of_") :] if type_name and type_name.startswith("list_of_") else type_name
    is_list = sep is not None or (type_name or "").startswith("list_of_")
    try:
        if not is_list:
            return _guess(text) if item_type is None else _SCALAR[item_type](text)
        if sep is not None:
            items = [item.strip() for item in text.split(sep)] if text.strip() else []
            return _uniform([_guess(i) if item_type is None else _SCALAR[item_type](i) for i in items], text)
        value = yaml.safe_load(text)
        if not isinstance(value, list):
            raise ValueError(text)
        return [_SCALAR[item_type](str(v).lower() if isinstance(v, bool) else str(v)) for v in value]  # type: ignore[index]
    except (ValueError, yaml.YAMLError):
        raise LaunchError(f"{text!r} is not a valid {type_name or 'list'}") from None


class Coercion:
    """A deferred `coerce` for values known only after substitution (the ParameterValue `value_type`)."""

    def __init__(self, type_name: str | None, sep: str | None) -> None:
        self.type_name, self.sep = type_name, sep
        self.__name__ = type_name or "value"

    def __call__(self, text: str) -> Any:
        return coerce(text, self.type_name, self.sep)


def guess_type(text: str) -> Any:
    """A substituted parameter value typed as ROS does: '1' → 1, 'true' → True, '[1, 2]' → [1, 2], else text."""
    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError:
        return text
    scalar = (bool, int, float)
    if isinstance(value, scalar) or (isinstance(value, list) and all(isinstance(v, (*scalar, str)) for v in value)):
        return value
    return text


class ParameterValue:
    """launch_ros's ParameterValue: a value with an explicit type (`value_type=str` keeps text as text)."""

    def __init__(self, value: Any, *, value_type: Any = None) -> None:
        self.value = value
        self.value_type = value_type


class Parameter:
    """launch_ros's Parameter (parameter_descriptions): one parameter of a node, given on its command line."""

    def __init__(self, name: SomeSubstitutions, value: Any, *, value_type: Any = None) -> None:
        self.name = normalize(name)
        self.value = ParameterValue(value, value_type=value_type)

    def evaluate(self, scope: Scope) -> tuple[str, Any]:
        return perform(self.name, scope), _param_value(self.value, scope)


@dataclass(frozen=True)
class CommandLineParameter:
    """A `Parameter` after substitution: `-p name:=text`, text as launch_ros writes it (`yaml.dump` of the
    value, so 5 is "5\\n...\\n" — rcl reads it back as YAML)."""

    name: str
    text: str


class ParameterFile:
    """launch_ros's ParameterFile: a parameters YAML; with `allow_substs=True` its `$(...)` are substituted."""

    def __init__(self, param_file: SomeSubstitutions | Path, *, allow_substs: bool | SomeSubstitutions = False) -> None:
        self.param_file = normalize(str(param_file) if isinstance(param_file, Path) else param_file)
        self.allow_substs = allow_substs

    def evaluate(self, scope: Scope) -> str:
        path = Path(perform(self.param_file, scope))
        if not path.is_file():
            raise LaunchError(f"parameter file {path} does not exist")
        allow = self.allow_substs
        if not isinstance(allow, bool):
            from diffctl.launch_legacy.conditions import truth

            allow = truth(perform(allow, scope), "allow_substs")
        if not allow:
            return str(path.resolve())
        text = perform(parse(path.read_text()), scope)
        out = Path(tempfile.mkdtemp(prefix="diffctl-params-")) / path.name
        out.write_text(text)
        return str(out)


def _param_value(value: Any, scope: Scope) -> Any:
    from diffctl.launch_legacy.conditions import truth

    if isinstance(value, ParameterValue):
        if value.value_type is None:
            return _param_value(value.value, scope)
        raw = value.value
        text = perform(raw, scope) if isinstance(raw, (Substitution, list, tuple, str)) else raw
        name = getattr(value.value_type, "__name__", str(value.value_type))
        try:
            return value.value_type(text) if value.value_type is not bool else truth(str(text), "ParameterValue")
        except (TypeError, ValueError):
            raise LaunchError(f"parameter value {text!r} is not a {name}") from None
    if isinstance(value, Substitution) or (
        isinstance(value, (list, tuple))
        and value
        and all(isinstance(v, (str, Substitution)) for v in value)
        and any(isinstance(v, Substitution) for v in value)
    ):
        return guess_type(perform(value, scope))
    if isinstance(value, (list, tuple)):
        return [_param_value(v, scope) for v in value]
    if isinstance(value, Mapping):
        return {str(k): _param_value(v, scope) for k, v in value.items()}
    return value


def flatten(values: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    """{'a': {'b': 1}} → {'a.b': 1}, as launch_ros flattens nested parameter dicts."""
    out: dict[str, Any] = {}
    for key, value in values.items():
        full = f"{prefix}{key}"
        if isinstance(value, Mapping):
            out.update(flatten(value, full + "."))
        else:
            out[full] = value
    return out


def resolve_parameters(entries: Iterable[Any], scope: Scope) -> tuple[str | dict[str, Any] | CommandLineParameter, ...]:
    """Parameter files and dicts in order; consecutive dicts merge, as they would on the node."""
    out: list[str | dict[str, Any] | CommandLineParameter] = []
    for entry in entries:
        if isinstance(entry, Mapping):
            values = {
                perform(k, scope) if not isinstance(k, str) else k: _param_value(v, scope) for k, v in entry.items()
            }
            if out and isinstance(out[-1], dict):
                out[-1].update(values)
            else:
                out.append(values)
            continue
        if isinstance(entry, ParameterFile):
            out.append(entry.evaluate(scope))
            continue
        if isinstance(entry, Parameter):
            name, value = entry.evaluate(scope)
            out.append(CommandLineParameter(name, yaml.dump(value)))
            continue
        path = Path(perform(entry, scope) if not isinstance(entry, Path) else str(entry))
        if not path.is_file():
            raise LaunchError(f"parameter file {path} does not exist")
        out.append(str(path.resolve()))
    return tuple(out)
