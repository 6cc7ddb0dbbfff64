"""launch_pytest's waits when what they wait for already happened: a test that begins after its process started,
or exited, is told so at once (not after its timeout, with False)."""

import sys

import launch_pytest
import launch_testing
import pytest
from launch_pytest import tools

import launch


@pytest.fixture(scope="module")
def quick():
    return launch.actions.ExecuteProcess(cmd=[sys.executable, "-c", "print('done')"], cached_output=True)


@launch_pytest.fixture(scope="module")
def launch_description(quick):
    return launch.LaunchDescription([quick, launch_testing.util.KeepAliveProc()])


@pytest.mark.launch(fixture=launch_description)
def test_1_waits_for_the_exit(quick, launch_context):
    assert tools.wait_for_exit_sync(launch_context, quick, timeout=60)


@pytest.mark.launch(fixture=launch_description)
def test_2_after_the_fact(quick, launch_context):
    assert tools.wait_for_start_sync(launch_context, quick, timeout=1)
    assert tools.wait_for_exit_sync(launch_context, quick, timeout=1)
    tools.assert_output_sync(launch_context, quick, lambda out: _equal(out, "done\n"), timeout=1)


@pytest.mark.launch(fixture=launch_description)
async def test_3_after_the_fact_async(quick, launch_context):
    assert await tools.wait_for_start(launch_context, quick, timeout=1)
    assert await tools.wait_for_exit(launch_context, quick, timeout=1)


def _equal(out, expected):
    assert out == expected
