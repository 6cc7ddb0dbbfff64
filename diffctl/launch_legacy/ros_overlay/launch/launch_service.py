"""`launch.launch_service.LaunchService`: a launch run on a thread of its own (diffctl/testing/service.py)."""

from diffctl.testing.service import LaunchService

__all__ = ["LaunchService"]
