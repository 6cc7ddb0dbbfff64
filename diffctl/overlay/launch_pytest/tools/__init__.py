"""`launch_pytest.tools` (diffctl/testing/launch_pytest.py)."""

from . import process  # noqa: F401
from .process import *  # noqa: F403
from .process import __all__  # noqa: F401
