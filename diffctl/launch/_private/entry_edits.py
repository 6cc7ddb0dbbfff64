"""The actions that change one entry of a table of the context: the environment, the launch configurations.

Set, append, unset: each performs its operands (the entry's name first) when executed and applies one
edit to its table. The operands live in `_fields`; the public classes show them with `field` properties.
"""

from __future__ import annotations

from collections.abc import MutableMapping
from typing import TYPE_CHECKING, Any, ClassVar

from ..action import Action
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions
from .markup import substitution_attributes

if TYPE_CHECKING:
    from ..frontend.entity import Entity
    from ..frontend.parser import Parser
    from ..launch_context import LaunchContext


class EntryEdit(Action):
    """Base of those actions. Subclasses say which table, which markup attributes, and what the edit is."""

    # markup attributes read as substitutions by `parse`: required, then optional
    _attributes: ClassVar[tuple[str, ...]] = ('name',)
    _optional_attributes: ClassVar[tuple[str, ...]] = ()

    def _take(self, **operands: Any) -> None:
        self._fields = {key: normalize_to_list_of_substitutions(value) for key, value in operands.items()}

    @classmethod
    def parse(cls, entity: Entity, parser: Parser):
        _, kwargs = super().parse(entity, parser)
        kwargs.update(substitution_attributes(entity, parser, cls._attributes, cls._optional_attributes))
        return cls, kwargs

    def _table(self, context: LaunchContext) -> MutableMapping[str, str]:
        raise NotImplementedError

    def _apply(self, context: LaunchContext, table: MutableMapping[str, str], texts: dict[str, str]) -> None:
        raise NotImplementedError

    def execute(self, context: LaunchContext) -> None:
        texts = {key: perform_substitutions(context, subs) for key, subs in self._fields.items()}
        self._apply(context, self._table(context), texts)


class EnvironmentEdit(EntryEdit):
    """An edit of the launch's environment (which is this process's `os.environ`)."""

    def _table(self, context: LaunchContext) -> MutableMapping[str, str]:
        return context.environment


class ConfigurationEdit(EntryEdit):
    """An edit of the launch configurations."""

    def _table(self, context: LaunchContext) -> MutableMapping[str, str]:
        return context.launch_configurations


def assign(context: LaunchContext, table: MutableMapping[str, str], texts: dict[str, str]) -> None:
    """The `set` edit: the entry `name` becomes `value`."""
    table[texts['name']] = texts['value']


def remove(context: LaunchContext, table: MutableMapping[str, str], texts: dict[str, str]) -> None:
    """The `unset` edit: the entry `name` goes, if it is there."""
    table.pop(texts['name'], None)
