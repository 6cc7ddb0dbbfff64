"""`launch_pytest` (diffctl/testing/launch_pytest.py): launch fixtures and `@pytest.mark.launch` tests."""

from diffctl.testing.launch_pytest import fixture

from . import actions, tools  # noqa: F401

__all__ = ["fixture"]
