"""`launch_testing_ros.pytest`: its hooks are diffctl's pytest plugin (entry point diffctl_launch_testing)."""

from . import hooks  # noqa: F401
