"""`Substitution`: text computed when the launch runs."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ._private.ros_names import default_text

if TYPE_CHECKING:
    from .launch_context import LaunchContext


class Substitution:
    """Base of every substitution: `perform(context)` returns the text it stands for."""

    def __repr__(self) -> str:
        return default_text(self)  # under ROS's module names, as ros2 launch --print shows it

    def describe(self) -> str:
        """Human-readable form, used by introspection and error messages."""
        return repr(self)

    def perform(self, context: LaunchContext) -> str:
        """The substituted text; every concrete substitution overrides this."""
        raise NotImplementedError('perform() not implemented for Substitution base class.')
