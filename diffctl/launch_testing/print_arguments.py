"""`launch_test --show-args`: the arguments a test's launch description declares."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any


def _conditional_entities(entities: Iterable[Any], found: set[int]) -> None:
    """Collect (by id) the entities that are reached only when some condition holds: those listed by
    describe_conditional_sub_entities of the entity containing them."""
    for entity in entities:
        _conditional_entities(entity.describe_sub_entities(), found)
        for _, sub_entities in entity.describe_conditional_sub_entities():
            found.update(id(e) for e in sub_entities)
            _conditional_entities(sub_entities, found)


def print_arguments_of_launch_description(*, launch_description: Any) -> None:
    """Print each declared argument with its description and default; a '*' marks those declared only
    under a condition."""
    print("Arguments (pass arguments as '<name>:=<value>'):")
    arguments = launch_description.get_launch_arguments()
    conditional: set[int] = set()
    _conditional_entities(launch_description.entities, conditional)
    any_conditional = False
    for argument in arguments:
        starred = argument.condition is not None or id(argument) in conditional
        any_conditional |= starred
        text = f"\n    '{argument.name}':{'*' if starred else ''}\n        {argument.description}"
        if argument.default_value is not None:
            text += "\n        (default: " + " + ".join(s.describe() for s in argument.default_value) + ")"
        print(text)
    if not arguments:
        print("\n  No arguments.")
    elif any_conditional:
        print("\n* argument(s) which are only used if specific conditions occur")
