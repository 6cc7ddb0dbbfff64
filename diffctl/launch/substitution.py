"""`Substitution`: text computed when the launch runs."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .launch_context import LaunchContext


class Substitution:
    """Base of every substitution: `perform(context)` returns the text it stands for."""

    def describe(self) -> str:
        """Human-readable form, used by introspection and error messages."""
        return repr(self)

    def perform(self, context: LaunchContext) -> str:
        """The substituted text; every concrete substitution overrides this."""
        raise NotImplementedError('perform() not implemented for Substitution base class.')
