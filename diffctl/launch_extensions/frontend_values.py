"""Reading what launch.frontend's Entity API cannot return: a YAML mapping value and a list of actions under a
key other than `children`.

`Entity.get_attr` returns scalars, uniform lists and lists of attribute entities; diffctl's tags also take
`replace: {PLACEHOLDER: value}` and `do: [{node: …}, …]` (both in the tutorial's launch files). diffctl's
launch_yaml Entity gives the YAML values it wraps (`yaml_value`, `get_yaml_attr`); ROS's has no such accessor,
so these tags need diffctl's launch_yaml (the one `diffctl launch` always loads).
"""

from __future__ import annotations

from typing import Any

from diffctl.errors import LaunchError


def _element(entity: Any) -> Any:
    """The YAML value a launch_yaml Entity wraps."""
    if not hasattr(entity, "yaml_value"):
        raise LaunchError(f"cannot read the value of `{entity.type_name}`: not an entity of diffctl's launch_yaml")
    return entity.yaml_value


def is_yaml(entity: Any) -> bool:
    """Whether the entity comes from the YAML frontend (launch_yaml's, or diffctl's module of that name)."""
    return "launch_yaml" in type(entity).__module__.split(".")


def mapping(entity: Any, name: str) -> dict[str, Any] | None:
    """A mapping-valued attribute of a YAML entity (`replace: {A: b}`), None when absent."""
    _element(entity)  # a YAML entity of diffctl's
    value = entity.get_yaml_attr(name, optional=True)
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
