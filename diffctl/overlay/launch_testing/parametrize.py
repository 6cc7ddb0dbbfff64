"""`launch_testing.parametrize` (diffctl/testing/decorators.py)."""

from diffctl.testing.decorators import parametrize

__all__ = ["parametrize"]
