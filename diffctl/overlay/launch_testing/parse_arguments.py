"""`launch_testing.parse_arguments` (diffctl/testing/parse_arguments.py)."""

from diffctl.testing.parse_arguments import parse_launch_arguments

__all__ = ["parse_launch_arguments"]
