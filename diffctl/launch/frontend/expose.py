"""The registry of the tags and substitution names the markup frontends understand.

`@expose_action('tag')` on an Action class (or on a parse function) says how an element of that tag
becomes an action: `parse(entity, parser)` returns `(a callable, its keyword arguments)`, usually the class
and its constructor's. `@expose_substitution('name')` does the same for `$(name args…)`, whose `parse(data)`
gets the arguments (each a list of substitutions). Third-party packages register theirs the same way, from
a module the `launch.frontend.launch_extension` entry point group names.
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..action import Action
    from ..some_substitutions_type import SomeSubstitutionsType
    from ..substitution import Substitution
    from .entity import Entity
    from .parser import Parser

action_parse_methods: dict[str, Any] = {}
substitution_parse_methods: dict[str, Any] = {}


def where(entity: Any) -> str:
    """'file:line: ' for an entity that knows where it was read, else ''."""
    location = getattr(entity, 'location', None)
    return f'{location}: ' if location else ''


def _builtins_loaded() -> None:
    # launch's own actions and substitutions are imported lazily: their decorators must have run
    from .._private.builtins import load_builtin_frontend_names

    load_builtin_frontend_names()


def instantiate_action(entity: Entity, parser: Parser) -> Action:
    """The action `entity` describes, made by the parse method registered for its tag."""
    _builtins_loaded()
    parse = action_parse_methods.get(entity.type_name)
    if parse is None:
        raise RuntimeError(f'{where(entity)}Unrecognized entity of the type: {entity.type_name}')
    make, kwargs = parse(entity, parser)
    return make(**kwargs)


def instantiate_substitution(type_name: str, args: Iterable[SomeSubstitutionsType] | None = None) -> Substitution:
    """The substitution `$(type_name args…)`, made by the parse method registered for that name."""
    _builtins_loaded()
    parse = substitution_parse_methods.get(type_name)
    if parse is None:
        raise RuntimeError(f'Unknown substitution: {type_name}')
    make, kwargs = parse(list(args) if args is not None else [])
    return make(**kwargs)


def _parse_method_of(exposed: Any, kind: str, name: str) -> Callable:
    if inspect.isfunction(exposed):
        return exposed
    if not inspect.isclass(exposed):
        raise RuntimeError(
            f'Exposed {kind} parser for {name} is not a callable or a class containing a parse method')
    if 'parse' not in dir(exposed) or not inspect.ismethod(exposed.parse):
        raise RuntimeError("Did not find a class method called 'parse' in the class being decorated.")
    return exposed.parse


def _strict(parse: Callable) -> Callable:
    """An action's parse method that also refuses what it left unread (a misspelled attribute, say)."""
    @functools.wraps(parse)
    def parse_everything(entity: Entity, parser: Parser):
        made = parse(entity, parser)
        entity.assert_entity_completely_parsed()
        return made

    return parse_everything


def _registrar(name: str, registry: dict[str, Any], kind: str) -> Callable:
    """The decorator `expose_action(name)` / `expose_substitution(name)` returns.

    The same parse method may be registered twice under a name (a module imported under two names),
    a different one may not.
    """
    def register(exposed: Any) -> Any:
        parse = _parse_method_of(exposed, kind, name)
        taken = registry.get(name)
        if taken is not None and getattr(taken, '__wrapped__', taken) != parse:
            raise RuntimeError(f'Two {kind} parsing methods exposed with the same name: [{name}].')
        registry[name] = _strict(parse) if kind == 'action' else parse
        return exposed

    return register


def expose_action(name: str):
    """Register an action class (its `parse` classmethod), or a parse function, for the tag `name`."""
    return _registrar(name, action_parse_methods, 'action')


def expose_substitution(name: str):
    """Register a substitution class (its `parse` classmethod), or a parse function, as `$(name …)`."""
    return _registrar(name, substitution_parse_methods, 'substitution')
