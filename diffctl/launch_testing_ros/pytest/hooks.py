"""The collector of a `@pytest.mark.rostest` launch test file: launch_testing's, run by launch_testing_ros'
LaunchTestRunner."""

from __future__ import annotations

from typing import Any

from diffctl.launch_testing.pytest.hooks import LaunchTestItem, LaunchTestModule


class LaunchROSTestItem(LaunchTestItem):
    @classmethod
    def from_parent(cls, *args: Any, **kwargs: Any) -> Any:  # type: ignore[override]
        from ..test_runner import LaunchTestRunner

        kwargs["runner_cls"] = LaunchTestRunner
        return super().from_parent(*args, **kwargs)


class LaunchROSTestModule(LaunchTestModule):
    def makeitem(self, *args: Any, **kwargs: Any) -> Any:
        return LaunchROSTestItem.from_parent(*args, **kwargs)
