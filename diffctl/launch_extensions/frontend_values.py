"""Reading what launch.frontend's Entity API cannot return: a YAML mapping value and a list of actions under a
key other than `children`.

`Entity.get_attr` returns scalars, uniform lists and lists of attribute entities; diffctl's tags also take
`replace: {PLACEHOLDER: value}` and `do: [{node: …}, …]` (both in the tutorial's launch files). launch_yaml's
Entity keeps the YAML value it wraps as upstream's class stores it; these helpers read it there, after
`get_attr` has marked the key as read (so `assert_entity_completely_parsed` accepts it).
"""

from __future__ import annotations

from typing import Any

from diffctl.errors import LaunchError


def _element(entity: Any) -> Any:
    """The YAML value a launch_yaml Entity wraps."""
    for cls in type(entity).__mro__:
        value = getattr(entity, f"_{cls.__name__}__element", None)
        if value is not None:
            return value
    raise LaunchError(f"cannot read the value of `{entity.type_name}`: not a YAML entity")


def is_yaml(entity: Any) -> bool:
    """Whether the entity comes from the YAML frontend (launch_yaml's, or diffctl's module of that name)."""
    return "launch_yaml" in type(entity).__module__.split(".")


def mapping(entity: Any, name: str) -> dict[str, Any] | None:
    """A mapping-valued attribute of a YAML entity (`replace: {A: b}`), None when absent."""
    try:
        value = entity.get_attr(name, data_type=None, optional=True)
    except TypeError:
        value = _element(entity).get(name)  # get_attr marked the key as read before refusing the type
    if value is None:
        return None
    if not isinstance(value, dict):
        raise LaunchError(f"`{entity.type_name}.{name}` must map names to values, got {value!r}")
    return {str(k): v for k, v in value.items()}


def action_entities(entity: Any, name: str) -> list[Any] | None:
    """The entities of `name: [{tag: {...}}, …]` (YAML) or of the entity's own children (XML, where actions
    nest as elements), ready for `parser.parse_action`; None when absent."""
    if not is_yaml(entity) or name == "children":
        return entity.children
    try:
        wrapped = entity.get_attr(name, data_type=_list_of_entities(), optional=True)
    except IndexError:
        return []  # an empty list: launch_yaml looks at its first item to tell what it holds
    except TypeError:
        raise LaunchError(
            f"`{entity.type_name}.{name}` must be a list of actions, e.g. `{name}: [{{log: {{message: hi}}}}]`"
        ) from None
    if wrapped is None:
        return None
    out = []
    for item in wrapped:
        raw = _element(item)
        if not isinstance(raw, dict) or len(raw) != 1:
            raise LaunchError(f"each entry of `{entity.type_name}.{name}` must be one action, like `- log: {{…}}`")
        ((tag, value),) = raw.items()
        out.append(type(entity)(value, tag, parent=entity))
    return out


def _list_of_entities() -> Any:
    from diffctl.launch.frontend import Entity

    return list[Entity]
