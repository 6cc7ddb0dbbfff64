"""`launch_testing.ready_to_test_action_timeout` (diffctl/testing/decorators.py)."""

from diffctl.testing.decorators import ready_to_test_action_timeout

__all__ = ["ready_to_test_action_timeout"]
