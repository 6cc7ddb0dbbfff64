"""The YAML frontend: ROS 2 YAML launch files (`launch:` + a list of one-key entities) → actions.

Tags and attributes follow the ROS 2 YAML frontend (`-` and `_` are interchangeable, as in `launch-prefix`);
every tag maps through the registry of action classes, and every error names file:line:column, the tag and
the attribute, with a close match when there is one.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import yaml

from diffctl.errors import LaunchError, suggest
from diffctl.launch import registry
from diffctl.launch.actions import Action, LaunchDescription
from diffctl.launch.conditions import IfCondition, UnlessCondition
from diffctl.launch.plan import Where
from diffctl.launch.readiness import parse_timeout, parse_wait_for
from diffctl.launch.substitutions import Substitution, parse


class MarkedDict(dict):
    """A YAML mapping that remembers where each key and value was written."""

    mark: yaml.Mark | None = None

    def __init__(self) -> None:
        super().__init__()
        self.key_marks: dict[Any, yaml.Mark] = {}
        self.value_marks: dict[Any, yaml.Mark] = {}


class MarkedList(list):
    mark: yaml.Mark | None = None

    def __init__(self, items: list[Any], marks: list[yaml.Mark]) -> None:
        super().__init__(items)
        self.item_marks = marks


class _Loader(yaml.SafeLoader):
    pass


def _construct_map(loader: _Loader, node: yaml.MappingNode) -> MarkedDict:
    loader.flatten_mapping(node)
    out = MarkedDict()
    out.mark = node.start_mark
    for key_node, value_node in node.value:
        if not isinstance(key_node, yaml.ScalarNode):
            m = key_node.start_mark
            raise LaunchError(
                "a mapping key must be a plain name or value, not a mapping or list (a stray ':' after one?)",
                line=m.line + 1,
                column=m.column + 1,
            )
        key = loader.construct_object(key_node, deep=True)
        if key in out:
            m = key_node.start_mark
            raise LaunchError(f"duplicate key {key!r}", line=m.line + 1, column=m.column + 1)
        out[key] = loader.construct_object(value_node, deep=True)
        out.key_marks[key] = key_node.start_mark
        out.value_marks[key] = value_node.start_mark
    return out


def _construct_seq(loader: _Loader, node: yaml.SequenceNode) -> MarkedList:
    out = MarkedList([loader.construct_object(n, deep=True) for n in node.value], [n.start_mark for n in node.value])
    out.mark = node.start_mark
    return out


_Loader.add_constructor("tag:yaml.org,2002:map", _construct_map)
_Loader.add_constructor("tag:yaml.org,2002:seq", _construct_seq)


def _where(source: str, mark: yaml.Mark | None) -> Where:
    return Where(source, mark.line + 1, mark.column + 1) if mark is not None else Where(source)


def _norm(key: Any) -> str:
    return str(key).replace("-", "_")


class Entity:
    """One YAML entity (`- node: {...}`) or sub-entity (a `param:` item), with typed, located accessors."""

    def __init__(self, tag: str, value: Any, source: str, mark: yaml.Mark | None, allowed: tuple[str, ...]) -> None:
        self.tag = tag
        self.source = source
        self.where = _where(source, mark)
        self.list_children: list[Any] | None = None
        if isinstance(value, list):
            self.list_children = value
            value = MarkedDict()
        elif value is None:
            value = MarkedDict()
        elif not isinstance(value, Mapping):
            raise self.error(f"`{tag}` takes a mapping of attributes, got {value!r}")
        self.attrs: dict[str, Any] = {}
        self.key_marks: dict[str, yaml.Mark] = {}
        self.value_marks: dict[str, yaml.Mark] = {}
        for key, item in value.items():
            name = _norm(key)
            km = getattr(value, "key_marks", {}).get(key)
            if name not in allowed:
                raise LaunchError(
                    f"unknown attribute {str(key)!r} of `{tag}`{suggest(name, allowed)}",
                    source=source,
                    line=km.line + 1 if km else None,
                    column=km.column + 1 if km else None,
                    hint="valid: " + ", ".join(allowed),
                )
            if name in self.attrs:
                raise self.error(f"attribute {name!r} given twice", key=name)
            self.attrs[name] = item
            if km is not None:
                self.key_marks[name] = km
                self.value_marks[name] = getattr(value, "value_marks", {})[key]

    # ---- errors ----------------------------------------------------------------------------------------------

    def where_of(self, key: str | None) -> Where:
        if key and key in self.value_marks:
            return _where(self.source, self.value_marks[key])
        return self.where

    def error(self, message: str, key: str | None = None, hint: str | None = None) -> LaunchError:
        w = self.where_of(key)
        field = f"{self.tag}.{key}" if key else self.tag
        return LaunchError(message, source=w.source, line=w.line, column=w.column, field=field, hint=hint)

    # ---- accessors -------------------------------------------------------------------------------------------

    def has(self, key: str) -> bool:
        return key in self.attrs

    def raw(self, key: str) -> Any:
        return self.attrs.get(key)

    def parse(self, text: str, key: str | None = None) -> tuple[Substitution, ...]:
        try:
            return parse(text)
        except LaunchError as e:
            w = self.where_of(key)
            e.source, e.line, e.column = w.source, w.line, w.column
            e.field = e.field or (f"{self.tag}.{key}" if key else self.tag)
            raise

    def text(self, key: str, required: bool = False) -> tuple[Substitution, ...] | None:
        if key not in self.attrs or self.attrs[key] is None:
            if required:
                raise self.error(f"`{self.tag}` needs `{key}`", key=None)
            return None
        value = self.attrs[key]
        if isinstance(value, bool):
            value = str(value).lower()
        elif isinstance(value, (int, float)):
            value = str(value)
        if not isinstance(value, str):
            raise self.error(f"`{key}` must be text, got {type(value).__name__}", key=key)
        return self.parse(value, key)

    def plain(self, key: str, required: bool = False) -> str | None:
        if key not in self.attrs or self.attrs[key] is None:
            if required:
                raise self.error(f"`{self.tag}` needs `{key}`")
            return None
        value = self.attrs[key]
        if isinstance(value, (Mapping, list)):
            raise self.error(f"`{key}` must be text", key=key)
        return str(value).lower() if isinstance(value, bool) else str(value)

    def boolean(self, key: str, default: bool) -> bool:
        value = self.attrs.get(key)
        if value is None:
            return default
        if isinstance(value, bool):
            return value
        word = str(value).strip().lower()
        if word in ("true", "1", "false", "0"):
            return word in ("true", "1")
        raise self.error(f"`{key}` is {value!r}, not a boolean", key=key, hint="valid: true, false")

    def value(self, key: str) -> Any:
        """A parameter value: YAML-typed; a string is a substitution, typed by YAML rules once substituted, as
        launch_yaml hands it to launch_ros (`value: "true"` is the boolean true, `value: "5"` the integer 5)."""

        def convert(v: Any) -> Any:
            if isinstance(v, str):
                return self.parse(v, key)
            if isinstance(v, list):
                return [convert(x) for x in v]
            if isinstance(v, Mapping):
                return {str(k): convert(x) for k, x in v.items()}
            return v

        return convert(self.attrs.get(key))

    def items(self, key: str, allowed: tuple[str, ...]) -> list[Entity]:
        """Sub-entities under `key` (`param:`, `remap:`, `env:`, `arg:`): a list of mappings."""
        raw = self.attrs.get(key)
        if raw is None:
            return []
        if isinstance(raw, Mapping):
            raw = MarkedList([raw], [getattr(raw, "mark", None)])
        if not isinstance(raw, list):
            raise self.error(f"`{key}` must be a list of mappings", key=key)
        marks = getattr(raw, "item_marks", [None] * len(raw))
        return [
            Entity(key, item, self.source, mark or self.value_marks.get(key), allowed)
            for item, mark in zip(raw, marks, strict=True)
        ]

    def children(self, key: str = "children") -> list[Action]:
        if self.list_children is not None and key == "children":
            return parse_entities(self.list_children, self.source)
        raw = self.attrs.get(key)
        if raw is None:
            return []
        if not isinstance(raw, list):
            raise self.error(f"`{key}` must be a list of entities", key=key)
        return parse_entities(raw, self.source)


def parse_entities(items: list[Any], source: str) -> list[Action]:
    marks = getattr(items, "item_marks", [None] * len(items))
    return [_entity(item, source, mark) for item, mark in zip(items, marks, strict=True)]


def _entity(item: Any, source: str, mark: yaml.Mark | None) -> Action:
    where = _where(source, mark)
    if not isinstance(item, Mapping) or len(item) != 1:
        keys = ", ".join(map(str, item)) if isinstance(item, Mapping) else repr(item)
        raise LaunchError(
            f"each entity is a mapping with one tag, found {keys}",
            source=where.source,
            line=where.line,
            column=where.column,
            hint="valid tags: " + ", ".join(sorted(registry.actions())),
        )
    ((raw_tag, value),) = item.items()
    tag = _norm(raw_tag)
    tag_mark = getattr(item, "key_marks", {}).get(raw_tag, mark)
    try:
        allowed = registry.attributes(tag)
    except LaunchError as e:
        raise where.attach(e) from None
    e = Entity(tag, value, source, tag_mark, allowed)
    try:
        action = registry.lookup(tag).from_entity(e)
    except LaunchError as err:
        raise e.where.attach(err, tag) from None
    return attach_common(action, e)


def attach_common(action: Action, e: Entity) -> Action:
    """What every entity of every frontend may carry: `if` / `unless`, readiness, and where it was written."""
    tag = e.tag
    if e.has("if") and e.has("unless"):
        raise e.error("give `if` or `unless`, not both", key="unless")
    if e.has("if"):
        action.condition = IfCondition(e.text("if"))
    elif e.has("unless"):
        action.condition = UnlessCondition(e.text("unless"))
    try:
        if e.has("wait_for"):
            action.wait_for = parse_wait_for(e.raw("wait_for"), lambda s: e.parse(s, "wait_for"))
        if e.has("wait_timeout"):
            action.wait_timeout = parse_timeout(e.raw("wait_timeout"))
    except LaunchError as err:
        raise e.where_of("wait_for").attach(err, f"{tag}.wait_for") from None
    action.where = e.where
    return action


def load(path: str | Path) -> LaunchDescription:
    source = str(path)
    try:
        text = Path(path).read_text()
    except FileNotFoundError:
        raise LaunchError("launch file does not exist", source=source) from None
    except OSError as e:
        raise LaunchError(f"cannot read launch file: {e.strerror}", source=source) from None
    except UnicodeDecodeError as e:
        raise LaunchError(f"not a UTF-8 text file (byte {e.start}: {e.reason})", source=source) from None
    try:
        data = yaml.load(text, Loader=_Loader)
    except yaml.MarkedYAMLError as e:
        mark = e.problem_mark or e.context_mark
        raise LaunchError(
            f"malformed YAML: {e.problem or e.context}",
            source=source,
            line=mark.line + 1 if mark else None,
            column=mark.column + 1 if mark else None,
        ) from None
    except yaml.YAMLError as e:  # the reader's (unacceptable characters) carry no problem mark
        raise LaunchError(f"malformed YAML: {e}", source=source) from None
    except LaunchError as e:
        e.source = source
        raise
    if not isinstance(data, Mapping) or set(data) != {"launch"}:
        raise LaunchError(
            "a YAML launch file is one mapping `launch:` holding a list of entities", source=source, line=1, column=1
        )
    entities = data["launch"] or []
    if not isinstance(entities, list):
        raise LaunchError("`launch:` must hold a list of entities", source=source)
    return LaunchDescription(parse_entities(entities, source))
