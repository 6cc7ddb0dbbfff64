"""`launch_pytest.plugin` (diffctl/testing/launch_pytest.py)."""

from diffctl.testing.launch_pytest import *  # noqa: F403
