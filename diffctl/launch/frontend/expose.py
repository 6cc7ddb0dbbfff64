"""The registry of tags and substitution names the frontends understand.

`@expose_action('tag')` on an Action class (or on a parse function) registers how a markup element of that
tag becomes an action: the class's `parse(entity, parser)` returns `(action class, constructor kwargs)`.
`@expose_substitution('name')` does the same for `$(name args…)`: `parse(data)` receives the arguments
(each a list of substitutions) and returns `(substitution class, kwargs)`. Third-party packages register
theirs the same way, imported through the `launch.frontend.launch_extension` entry point group.
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..action import Action
    from ..some_substitutions_type import SomeSubstitutionsType
    from ..substitution import Substitution
    from .entity import Entity
    from .parser import Parser

action_parse_methods: dict[str, Any] = {}
substitution_parse_methods: dict[str, Any] = {}


def _load_builtins() -> None:
    from .._private.builtins import load_builtin_frontend_names

    load_builtin_frontend_names()


def where(entity: Any) -> str:
    """'file:line: ' for an entity that knows where it was read from, '' otherwise."""
    location = getattr(entity, 'location', None)
    return f'{location}: ' if location else ''


def instantiate_action(entity: Entity, parser: Parser) -> Action:
    """The action an entity describes, built by the parse method registered for its tag."""
    _load_builtins()
    parse = action_parse_methods.get(entity.type_name)
    if parse is None:
        raise RuntimeError(f'{where(entity)}Unrecognized entity of the type: {entity.type_name}')
    action_type, kwargs = parse(entity, parser)
    return action_type(**kwargs)


def instantiate_substitution(
    type_name: str, args: Iterable[SomeSubstitutionsType] | None = None
) -> Substitution:
    """The substitution `$(type_name args…)`, built by the parse method registered for the name."""
    _load_builtins()
    parse = substitution_parse_methods.get(type_name)
    if parse is None:
        raise RuntimeError(f'Unknown substitution: {type_name}')
    substitution_type, kwargs = parse([] if args is None else args)
    return substitution_type(**kwargs)


def __expose_impl(name: str, parse_methods_map: dict, exposed_type: str):
    """A decorator registering a class's `parse` classmethod (or a parse function) under `name`.

    Registering a different parse method under a name already taken is a RuntimeError. Actions are
    checked after parsing: an attribute or child the parse method did not read is an error.
    """

    def decorator(exposed):
        if inspect.isclass(exposed):
            if not ('parse' in dir(exposed) and inspect.ismethod(exposed.parse)):
                raise RuntimeError("Did not find a class method called 'parse' in the class being decorated.")
            parse = exposed.parse
        elif inspect.isfunction(exposed):
            parse = exposed
        else:
            raise RuntimeError(
                f'Exposed {exposed_type} parser for {name} is not a callable or a class containing a parse method')
        known = parse_methods_map.get(name)
        if known is not None and getattr(known, '__wrapped__', known) != parse:
            raise RuntimeError(
                f'Two {exposed_type} parsing methods exposed with the same name: [{name}].')
        if exposed_type == 'action':
            @functools.wraps(parse)
            def checked(entity, parser):
                result = parse(entity, parser)
                entity.assert_entity_completely_parsed()
                return result

            parse_methods_map[name] = checked
        else:
            parse_methods_map[name] = parse
        return exposed

    return decorator


def expose_substitution(name: str):
    """Register a substitution class (its `parse` classmethod) or parse function as `$(name …)`."""
    return __expose_impl(name, substitution_parse_methods, 'substitution')


def expose_action(name: str):
    """Register an action class (its `parse` classmethod) or parse function for the tag `name`."""
    return __expose_impl(name, action_parse_methods, 'action')
