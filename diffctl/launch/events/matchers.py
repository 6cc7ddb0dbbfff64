"""`matches_action`: select the events about one action."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..action import Action


def matches_action(target_action: Action) -> Callable[[Action], bool]:
    """A predicate on actions, true for `target_action` (by equality) only."""

    def is_target(action: Action) -> bool:
        return action == target_action

    # read by the launch context: an event for one action is offered to that action's handlers only
    is_target._target_action = target_action  # type: ignore[attr-defined]
    return is_target
