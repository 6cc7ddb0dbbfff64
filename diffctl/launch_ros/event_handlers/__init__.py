"""launch_ros's event handlers."""

from .on_state_transition import OnStateTransition

__all__ = ["OnStateTransition"]
