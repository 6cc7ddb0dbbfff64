"""`launch_testing_ros.pytest.hooks` (diffctl/testing/pytest_plugin.py): the launch test item and module of pytest."""

from diffctl.testing.pytest_plugin import LaunchTestItem as LaunchROSTestItem
from diffctl.testing.pytest_plugin import LaunchTestModule as LaunchROSTestModule

__all__ = ["LaunchROSTestItem", "LaunchROSTestModule"]
