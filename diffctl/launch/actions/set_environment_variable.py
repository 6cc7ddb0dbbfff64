"""`SetEnvironmentVariable`, `<set_env name=… value=…/>`."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .._private.entry_edits import EnvironmentEdit, assign
from .._private.fields import field
from ..frontend.expose import expose_action

if TYPE_CHECKING:
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_action('set_env')
class SetEnvironmentVariable(EnvironmentEdit):
    """Gives the environment variable `name` the value `value`; processes started later inherit it."""

    _attributes = ('name', 'value')
    _apply = staticmethod(assign)

    name = field('name', 'The variable, as substitutions.')
    value = field('value', 'Its new value, as substitutions.')

    def __init__(self, name: SomeSubstitutionsType, value: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self._take(name=name, value=value)
