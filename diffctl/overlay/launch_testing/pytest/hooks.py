"""`launch_testing.pytest.hooks` (diffctl/testing/pytest_plugin.py)."""

from diffctl.testing.pytest_plugin import *  # noqa: F403
