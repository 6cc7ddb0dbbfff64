"""`SetLaunchConfiguration`, `<let name=… value=…/>`."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .._private.entry_edits import ConfigurationEdit, assign
from .._private.fields import field
from ..frontend.expose import expose_action

if TYPE_CHECKING:
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_action('let')
class SetLaunchConfiguration(ConfigurationEdit):
    """Gives the launch configuration `name` the value `value`, for what is visited after it.

    Included files see it too; a scoped group forgets it at its end.
    """

    _attributes = ('name', 'value')
    _apply = staticmethod(assign)

    name = field('name', 'The configuration, as substitutions.')
    value = field('value', 'Its new value, as substitutions.')

    def __init__(self, name: SomeSubstitutionsType, value: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self._take(name=name, value=value)
