"""`launch_testing.asserts` (diffctl/testing/asserts.py)."""

from diffctl.testing.asserts import *  # noqa: F403
from diffctl.testing.asserts import SequentialTextChecker, __all__  # noqa: F401
from diffctl.testing.proc_lookup import NO_CMD_ARGS  # noqa: F401
