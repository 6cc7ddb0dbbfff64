"""launch_testing_ros' LaunchTestRunner: the files marked `rostest` run with it (launch_testing's)."""

from __future__ import annotations

from diffctl.launch_testing import test_runner


class LaunchTestRunner(test_runner.LaunchTestRunner):
    pass
