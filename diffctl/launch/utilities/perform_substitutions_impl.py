"""`perform_substitutions`: the text of a list of substitutions in a context."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..substitution import Substitution


def perform_substitutions(context: LaunchContext, subs: list[Substitution]) -> str:
    """Perform each substitution with `context` and concatenate the results."""
    return ''.join(context.perform_substitution(sub) for sub in subs)
