"""`UnsetLaunchConfiguration`: forget a launch configuration."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .._private.entry_edits import ConfigurationEdit, remove
from .._private.fields import field
from ..action import Action

if TYPE_CHECKING:
    from ..some_substitutions_type import SomeSubstitutionsType


class UnsetLaunchConfiguration(ConfigurationEdit):
    """Removes the launch configuration `name`; nothing happens when there is none."""

    _apply = staticmethod(remove)
    parse = staticmethod(Action.parse)  # no markup tag of its own

    name = field('name', 'The configuration, as substitutions.')

    def __init__(self, name: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self._take(name=name)
