"""The XML frontend: ROS 2 XML launch files (`<launch>` + one element per entity) → the same actions as YAML.

Tags and attributes are those of ROS 2's `launch_xml` (`-` and `_` are interchangeable, as in
`launch-prefix` / `push-ros-namespace`); every tag maps through the one registry of action classes, whose
`from_entity` reads an `XmlEntity` exactly as it reads a YAML entity. Attribute values are text, so `<param>`
values are typed as launch_xml types them (parameters.coerce). Errors name file:line, the tag and the
attribute, with a close match when there is one.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from lxml import etree

from diffctl.errors import LaunchError, suggest, xml_error
from diffctl.launch import registry
from diffctl.launch.actions import Action, LaunchDescription
from diffctl.launch.parameters import TYPES, Coercion, ParameterValue, coerce
from diffctl.launch.plan import Where
from diffctl.launch.substitutions import Substitution, is_static, parse
from diffctl.launch.yaml_frontend import attach_common

# Nested elements that are lists of sub-entities under another name in the model (YAML `choices: [..]`).
CHILD_KEYS = {"choice": "choices"}
# Attributes `<param>` takes in XML only: the text has a type to be read as, and lists a separator.
PARAM_EXTRAS = ("type", "value_sep", "allow_substs")
ACTION_CHILDREN = ("children", "do")
# What XML writes only as nested elements (YAML: lists of mappings).
NESTED_ONLY = ("param", "remap", "env", "arg", "keep", "choices", "wait_for")


def _norm(name: str) -> str:
    return name.replace("-", "_")


def _elements(element: Any) -> list[Any]:
    return [c for c in element if isinstance(c.tag, str)]  # comments and processing instructions are not entities


class XmlEntity:
    """One XML element as an entity: the accessor interface of yaml_frontend.Entity, over text attributes."""

    def __init__(self, element: Any, source: str, allowed: tuple[str, ...]) -> None:
        self.element = element
        self.tag = _norm(element.tag)
        self.source = source
        self.where = Where(source, element.sourceline)
        self.allowed = allowed
        self.attrs: dict[str, str] = {}
        for raw_name, value in element.attrib.items():
            name = _norm(raw_name)
            if name not in allowed or name in ACTION_CHILDREN:
                valid = [a for a in allowed if a not in ACTION_CHILDREN]
                raise self.error(
                    f"unknown attribute {raw_name!r} of <{element.tag}>{suggest(name, valid)}",
                    hint="valid: " + ", ".join(a.replace("_", "-") if a == "launch_prefix" else a for a in valid),
                )
            if name in NESTED_ONLY:
                raise self.error(
                    f"`{raw_name}` is written as nested elements in XML, not as an attribute",
                    hint=f'e.g. <{element.tag} …><{raw_name} name="…" value="…"/></{element.tag}>',
                )
            if name in self.attrs:
                raise self.error(f"attribute {raw_name!r} given twice (- and _ are the same)", key=name)
            self.attrs[name] = value
        self.sub: dict[str, list[Any]] = {}
        self.actions: list[Any] = []
        takes_actions = any(k in allowed for k in ACTION_CHILDREN)
        for child in _elements(element):
            key = CHILD_KEYS.get(child.tag, _norm(child.tag))
            if key in allowed and key not in ACTION_CHILDREN:
                if key in self.attrs:
                    raise XmlEntity._at(child, source, f"`{key}` given both as attribute and as nested <{child.tag}>")
                self.sub.setdefault(key, []).append(child)
            elif takes_actions:
                self.actions.append(child)
            else:
                nested = [k for k in allowed if k not in self.attrs and k not in ACTION_CHILDREN]
                raise XmlEntity._at(
                    child,
                    source,
                    f"unexpected nested tag <{child.tag}> in <{element.tag}>{suggest(key, nested)}",
                    hint=f"<{element.tag}> holds no launch actions",
                )

    @staticmethod
    def _at(element: Any, source: str, message: str, hint: str | None = None) -> LaunchError:
        return LaunchError(message, source=source, line=element.sourceline, field=_norm(element.tag), hint=hint)

    # ---- errors ----------------------------------------------------------------------------------------------

    def where_of(self, key: str | None) -> Where:
        return self.where

    def error(self, message: str, key: str | None = None, hint: str | None = None) -> LaunchError:
        field = f"{self.tag}.{key}" if key else self.tag
        return LaunchError(message, source=self.source, line=self.where.line, field=field, hint=hint)

    # ---- accessors (as yaml_frontend.Entity) -----------------------------------------------------------------

    def has(self, key: str) -> bool:
        return key in self.attrs or key in self.sub

    def raw(self, key: str) -> Any:
        if key == "wait_for" and key in self.sub:
            return [self._wait(c) for c in self.sub[key]]
        if key == "choices" and key in self.sub:
            return [XmlEntity(c, self.source, ("value",)).plain("value", required=True) for c in self.sub[key]]
        value = self.attrs.get(key)
        if key == "exit_code" and value is not None:
            try:
                return int(value)
            except ValueError:
                raise self.error(f"exit_code {value!r} must be an integer", key=key) from None
        return value

    def _wait(self, element: Any) -> dict[str, Any]:
        """`<wait_for exited="spawn_entity"/>`, `<wait_for log="sim" regex="ready"/>` → the YAML shape."""
        attrs = dict(element.attrib)
        if "log" in attrs:
            if set(attrs) != {"log", "regex"}:
                raise XmlEntity._at(element, self.source, '<wait_for log="PROCESS" regex="PATTERN"/> takes those two')
            return {"log": {"process": attrs["log"], "regex": attrs["regex"]}}
        if len(attrs) != 1:
            raise XmlEntity._at(
                element,
                self.source,
                "<wait_for> takes one condition",
                hint='e.g. <wait_for exited="spawn_entity"/>, <wait_for topic="/robot_description"/>',
            )
        return attrs

    def parse(self, text: str, key: str | None = None) -> tuple[Substitution, ...]:
        try:
            return parse(text)
        except LaunchError as e:
            e.source, e.line, e.column = self.source, self.where.line, None
            e.field = e.field or (f"{self.tag}.{key}" if key else self.tag)
            raise

    def text(self, key: str, required: bool = False) -> tuple[Substitution, ...] | None:
        if key not in self.attrs:
            if required:
                raise self.error(f"<{self.element.tag}> needs the attribute `{key}`")
            return None
        return self.parse(self.attrs[key], key)

    def plain(self, key: str, required: bool = False) -> str | None:
        if key not in self.attrs:
            if required:
                raise self.error(f"<{self.element.tag}> needs the attribute `{key}`")
            return None
        return self.attrs[key]

    def boolean(self, key: str, default: bool) -> bool:
        value = self.attrs.get(key)
        if value is None:
            return default
        word = value.strip().lower()
        if word in ("true", "1", "false", "0"):
            return word in ("true", "1")
        raise self.error(f"`{key}` is {value!r}, not a boolean", key=key, hint="valid: true, false")

    def value(self, key: str) -> Any:
        """A `<param value=…>`: typed by its `type` / `value-sep` now, or after substitution when it has any."""
        text = self.attrs.get(key)
        if text is None:
            return None
        type_name, sep = self.attrs.get("type"), self.attrs.get("value_sep")
        parts = self.parse(text, key)
        if type_name is not None and type_name not in TYPES:
            raise self.error(
                f"parameter type {type_name!r} is not valid", key="type", hint="valid: " + ", ".join(TYPES)
            )
        try:
            if is_static(parts):
                return coerce(text, type_name, sep)
        except LaunchError as e:
            raise self.error(f"parameter {self.attrs.get('name', '?')!r}: {e.message}", key=key, hint=e.hint) from None
        if type_name is None and sep is None:
            return parts  # typed from YAML after substitution, as launch_ros does
        return ParameterValue(parts, value_type=Coercion(type_name, sep))

    def items(self, key: str, allowed: tuple[str, ...]) -> list[XmlEntity]:
        extra = PARAM_EXTRAS if key == "param" else ()
        return [XmlEntity(c, self.source, allowed + extra) for c in self.sub.get(key, [])]

    def children(self, key: str = "children") -> list[Action]:
        if key not in ACTION_CHILDREN:
            raise self.error(f"`{key}` takes a list of actions, which XML launch files cannot give", key=key)
        return parse_elements(self.actions, self.source)


def _check_param(e: XmlEntity) -> None:
    """launch_ros's `<param>` rules, checked before the YAML-shaped reading takes over."""
    if e.has("from") and e.has("name"):
        raise e.error("name and from attributes are mutually exclusive")
    if e.has("name") and not e.has("value") and not e.has("param"):
        raise e.error(f"parameter {e.attrs['name']!r}: either a value attribute or nested params are needed")
    if e.has("param") and (e.has("value") or e.has("type")):
        raise e.error("a <param> with nested params takes no value or type")
    for child in e.items("param", ("name", "value", "from", "param")):
        _check_param(child)


def _entity(element: Any, source: str) -> Action:
    tag = _norm(element.tag)
    where = Where(source, element.sourceline)
    try:
        allowed = registry.attributes(tag)
    except LaunchError as e:
        e.message = f"unknown tag <{element.tag}>" + e.message[len(f"unknown tag {tag!r}") :]
        raise where.attach(e) from None
    e = XmlEntity(element, source, allowed)
    for param in e.items("param", ("name", "value", "from", "param")) if "param" in allowed else ():
        _check_param(param)
    try:
        action = registry.lookup(tag).from_entity(e)  # type: ignore[arg-type]
    except LaunchError as err:
        raise where.attach(err, tag) from None
    return attach_common(action, e)  # type: ignore[arg-type]


def parse_elements(elements: list[Any], source: str) -> list[Action]:
    return [_entity(el, source) for el in elements]


def load(path: str | Path) -> LaunchDescription:
    source = str(path)
    if not Path(path).is_file():
        raise LaunchError("launch file does not exist", source=source)
    parser = etree.XMLParser(remove_comments=True, remove_pis=True, resolve_entities=False, no_network=True)
    try:
        tree = etree.parse(str(path), parser)
    except etree.XMLSyntaxError as e:
        raise xml_error(e, source, kind=LaunchError) from None
    except OSError as e:
        raise LaunchError(f"cannot read launch file: {e}", source=source) from None
    root = tree.getroot()
    if root.tag != "launch":
        raise LaunchError(
            f"the root element is <{root.tag}>, not <launch>",
            source=source,
            line=root.sourceline,
            hint="an XML launch file is <launch> holding one element per entity",
        )
    unknown = [a for a in root.attrib if a != "version"]
    if unknown:
        raise LaunchError(f"unknown attribute {unknown[0]!r} of <launch>", source=source, line=root.sourceline)
    return LaunchDescription(parse_elements(_elements(root), source))
