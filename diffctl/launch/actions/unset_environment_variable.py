"""`UnsetEnvironmentVariable`, `<unset_env name=…/>`."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .._private.entry_edits import EnvironmentEdit, remove
from .._private.fields import field
from ..frontend.expose import expose_action

if TYPE_CHECKING:
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_action('unset_env')
class UnsetEnvironmentVariable(EnvironmentEdit):
    """Takes the variable `name` out of the environment; nothing happens when it is not set."""

    _apply = staticmethod(remove)

    name = field('name', 'The variable, as substitutions.')

    def __init__(self, name: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self._take(name=name)
