"""`launch_testing.markers` (diffctl/testing/decorators.py)."""

from diffctl.testing.decorators import keep_alive, retry_on_failure

__all__ = ["keep_alive", "retry_on_failure"]
