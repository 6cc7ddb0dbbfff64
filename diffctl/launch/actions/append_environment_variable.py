"""`AppendEnvironmentVariable`, `<append_env name=… value=… [prepend=…] [separator=…]/>`."""

from __future__ import annotations

import os
from collections.abc import MutableMapping
from typing import TYPE_CHECKING, Any

from .._private.entry_edits import EnvironmentEdit
from .._private.fields import field
from .._private.markup import typed_attribute
from ..frontend.expose import expose_action
from ..utilities.type_utils import NormalizedValueType, normalize_typed_substitution, perform_typed_substitution

if TYPE_CHECKING:
    from ..frontend.entity import Entity
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_action('append_env')
class AppendEnvironmentVariable(EnvironmentEdit):
    """Extends the variable `name` with `value`, after what it holds or (`prepend`) before it.

    The two are joined by `separator` (the platform's path separator by default); a variable not set yet
    simply becomes `value`. `prepend` may be a substitution, read as a boolean when executed.
    """

    _attributes = ('name', 'value')
    _optional_attributes = ('separator',)

    name = field('name', 'The variable, as substitutions.')
    value = field('value', 'What is added, as substitutions.')
    separator = field('separator', 'What goes between the old and the added text.')

    def __init__(
        self,
        name: SomeSubstitutionsType,
        value: SomeSubstitutionsType,
        prepend: bool | SomeSubstitutionsType = False,
        separator: SomeSubstitutionsType = os.pathsep,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self._take(name=name, value=value, separator=separator)
        self._at_front = normalize_typed_substitution(prepend, bool)

    @property
    def prepend(self) -> NormalizedValueType:
        return self._at_front

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        made, kwargs = super().parse(entity, parser)
        at_front = typed_attribute(entity, parser, 'prepend', bool, optional=True)
        if at_front is not None:
            kwargs['prepend'] = at_front
        return made, kwargs

    def _apply(self, context: LaunchContext, table: MutableMapping[str, str], texts: dict[str, str]) -> None:
        key, added, between = texts['name'], texts['value'], texts['separator']
        before = table.get(key)
        if before is None:
            table[key] = added
        elif perform_typed_substitution(context, self._at_front, bool):
            table[key] = between.join((added, before))
        else:
            table[key] = between.join((before, added))
