"""`launch_testing.tools.process` (diffctl/testing/tools.py)."""

from diffctl.testing.tools import ProcessProxy, launch_process

__all__ = ["ProcessProxy", "launch_process"]
