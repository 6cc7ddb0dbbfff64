"""`launch_testing.print_arguments` (diffctl/testing/launch_test.py)."""

from diffctl.testing.launch_test import print_arguments_of_launch_description

__all__ = ["print_arguments_of_launch_description"]
