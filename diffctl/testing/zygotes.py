"""One preloaded interpreter for all the launch tests of a `diffctl test` run, so the test runner, launch and
diffctl's modules are imported once per run instead of once per test file.

`diffctl test` with launch tests to run starts one fork server (supervision's zygote, the one `diffctl launch`
uses) that imports what a test process imports (TEST_MODULES) and forks every launch test from it
(`python -m diffctl test-child …`, re-parented to `diffctl test`, a child subreaper, which waits and kills it
as a process it started). Each test keeps its own router and domain. The components a test's launch starts
are exec'd: the new launch core has no fork-server spawner yet (supervision's business); when it has, the
test's LaunchService gets it.
"""

from __future__ import annotations

from diffctl.supervision.zygote import Preload

TEST_MODULES = (
    "pytest",
    "diffctl.testing.launch_test",
    "diffctl.testing.runner",
    "diffctl.testing.junit",
    "diffctl.testing.isolation",
    "diffctl.launch_testing.test_runner",
    "diffctl.launch_testing.loader",
    "diffctl.launch_testing.asserts",
    "diffctl.launch_testing.tools",
    "diffctl.launch_pytest.plugin",
    "diffctl.launch_pytest.tools",
    "diffctl.launch.actions.execute_process",
    "diffctl.launch.launch_service",
    "diffctl.launch_ros.actions",
    "diffctl.bus.router",
    "diffctl.client",
    "diffctl.client.node",
)


def test_preload() -> Preload:
    """What a test process imports: the runners, launch, launch_ros and the client library. Not the components'
    modules: the test's launch execs its components (its LaunchService has no fork server to hand them to)."""
    return Preload(modules=TEST_MODULES)
