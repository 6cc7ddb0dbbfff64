"""Reading the attributes of a markup tag into an action's keyword arguments (shared by the `parse`s)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..frontend.entity import Entity
    from ..frontend.parser import Parser


def substitution_attributes(
    entity: Entity, parser: Parser, required: tuple[str, ...] = (), optional: tuple[str, ...] = (),
    *, renamed: dict[str, str] | None = None,
) -> dict[str, Any]:
    """Each attribute read as text and parsed into substitutions, keyed by its keyword argument.

    `required` ones must be there (the entity raises otherwise); `optional` ones are left out when absent.
    `renamed` maps an attribute to a keyword of another name (`message` → `msg`).
    """
    keyword = renamed or {}
    found: dict[str, Any] = {}
    for attribute, optional_one in [(a, False) for a in required] + [(a, True) for a in optional]:
        text = entity.get_attr(attribute, optional=optional_one)
        if text is not None:
            found[keyword.get(attribute, attribute)] = parser.parse_substitution(text)
    return found


def typed_attribute(entity: Entity, parser: Parser, attribute: str, data_type: type, *, optional: bool) -> Any:
    """An attribute that is a `data_type` value or text holding substitutions (`period`, `prepend`…).

    None when it is optional and absent.
    """
    value = entity.get_attr(attribute, data_type=data_type, optional=optional, can_be_str=True)
    return None if value is None else parser.parse_if_substitutions(value)


def name_value_children(entity: Entity, parser: Parser, tag: str) -> list[tuple[Any, Any]] | None:
    """The `<tag name=… value=…/>` children of `entity` as (name, value) substitution pairs; None if none.

    Each child must have nothing else.
    """
    from ..frontend.entity import Entity as EntityType

    children = entity.get_attr(tag, data_type=list[EntityType], optional=True)
    if children is None:
        return None
    pairs = [
        (parser.parse_substitution(child.get_attr('name')), parser.parse_substitution(child.get_attr('value')))
        for child in children
    ]
    for child in children:
        child.assert_entity_completely_parsed()
    return pairs


def kept_configurations(entity: Entity, parser: Parser) -> dict[Any, Any] | None:
    """`<keep name=… value=…/>` children as the {name: value} a group or a reset takes; None if none."""
    pairs = name_value_children(entity, parser, 'keep')
    # a name made of substitutions is a list, and a dict key must be hashable
    return None if pairs is None else {tuple(name): value for name, value in pairs}
