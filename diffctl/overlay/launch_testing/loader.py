"""`launch_testing.loader` (diffctl/testing/loader.py): TestRun and the loaders launch_test uses."""

from diffctl.testing.loader import (
    PostShutdownTestLoader,
    PreShutdownTestLoader,
    TestRun,
)
from diffctl.testing.loader import load_test_runs as LoadTestsFromPythonModule

__all__ = ["LoadTestsFromPythonModule", "PostShutdownTestLoader", "PreShutdownTestLoader", "TestRun"]
