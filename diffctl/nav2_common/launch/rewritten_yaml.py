"""`RewrittenYaml`: the path of a copy of a YAML file (a parameter file, usually) with values and keys rewritten.

What the rewrites do, in this order:
- `param_rewrites` keyed by a bare name set every mapping key of that name, at any depth (its whole value),
  innermost first; keyed by a dotted path of the file's leaves (`node.ros__parameters.a.b`, list items by index),
  that leaf. A dotted path through `ros__parameters` that the file lacks is added.
- `key_rewrites` rename mapping keys at any depth.
- `root_key`, when it is not empty, nests the whole under it.
Values come as text: 'true'/'false' (any case) become booleans, and with `convert_types` numbers become int or
float (float when the text has a '.').
"""

from __future__ import annotations

from typing import Any

import yaml

from diffctl.launch import LaunchContext, SomeSubstitutionsType, Substitution
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from ._files import read_yaml, write_copy


class RewrittenYaml(Substitution):
    def __init__(
        self,
        source_file: SomeSubstitutionsType,
        param_rewrites: dict,
        root_key: SomeSubstitutionsType | None = None,
        key_rewrites: dict | None = None,
        convert_types: bool = False,
    ) -> None:
        super().__init__()
        self._source = normalize_to_list_of_substitutions(source_file)
        self._params = {k: normalize_to_list_of_substitutions(v) for k, v in param_rewrites.items()}
        self._keys = {k: normalize_to_list_of_substitutions(v) for k, v in (key_rewrites or {}).items()}
        self._root = None if root_key is None else normalize_to_list_of_substitutions(root_key)
        self._convert_types = convert_types

    @property
    def name(self) -> list[Substitution]:
        return self._source

    def describe(self) -> str:
        return ""

    def perform(self, context: LaunchContext) -> str:
        data = read_yaml(perform_substitutions(context, self._source), "RewrittenYaml")
        values = {k: self._typed(perform_substitutions(context, v)) for k, v in self._params.items()}
        names = {k: perform_substitutions(context, v) for k, v in self._keys.items()}
        if data is None:
            data = {}
        _set_named(data, values)
        for path in leaf_paths(data) & values.keys():
            _set_at(data, path.split("."), values[path])
        for path in values.keys() - leaf_paths(data):
            if "ros__parameters" in path.split("."):
                _set_at(data, path.split("."), values[path])
        _rename(data, names)
        if self._root is not None:
            root = perform_substitutions(context, self._root)
            if root:
                data = {root: data}
        return write_copy(yaml.dump(data))

    def _typed(self, text: str) -> Any:
        if self._convert_types:
            try:
                return float(text) if "." in text else int(text)
            except ValueError:
                pass
        if text.lower() in ("true", "false"):
            return text.lower() == "true"
        return text


def leaf_paths(node: Any, prefix: str = "") -> set[str]:
    """Dotted paths of every scalar under `node`: mapping keys and list indices joined by '.'."""
    if isinstance(node, dict):
        items = ((str(k), v) for k, v in node.items())
    elif isinstance(node, list):
        items = ((str(i), v) for i, v in enumerate(node))
    else:
        return {prefix}
    out: set[str] = set()
    for key, child in items:
        out |= leaf_paths(child, f"{prefix}.{key}" if prefix else key)
    return out


def _set_named(mapping: Any, values: dict[str, Any]) -> None:
    """Every key named in `values`, at any depth of nested mappings, gets that value (deepest first)."""
    if not isinstance(mapping, dict):
        return
    for key in list(mapping):
        _set_named(mapping[key], values)
        if key in values:
            mapping[key] = values[key]


def _set_at(node: Any, path: list[str], value: Any) -> None:
    """Set the leaf at `path`, making the mappings on the way that are missing."""
    *parents, last = path
    for key in parents:
        node = node[int(key)] if isinstance(node, list) else node.setdefault(key, {})
    if isinstance(node, list):
        node[int(last)] = value
    else:
        node[last] = value


def _rename(mapping: Any, names: dict[str, str]) -> None:
    if not names or not isinstance(mapping, dict):
        return
    for key in list(mapping):
        value = mapping[key]
        if key in names:
            mapping[names[key]] = mapping.pop(key)
        _rename(value, names)
