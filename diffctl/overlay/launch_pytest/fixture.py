"""`launch_pytest.fixture` (diffctl/testing/launch_pytest.py)."""

from diffctl.testing.launch_pytest import fixture

__all__ = ["fixture"]
