"""`launch_pytest.tools`."""

from . import process  # noqa: F401
