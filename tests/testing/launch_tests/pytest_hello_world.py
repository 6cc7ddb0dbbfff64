"""launch_pytest as its examples use it: a launch fixture, cached output, sync/async/generator tests, shutdown."""

import sys

import launch_pytest
import pytest
from launch_pytest.tools import process as process_tools

import launch


@pytest.fixture
def hello_world_proc():
    return launch.actions.ExecuteProcess(cmd=["echo", "hello_world"], shell=True, cached_output=True)


@launch_pytest.fixture
def launch_description(hello_world_proc):
    return launch.LaunchDescription([hello_world_proc, launch_pytest.actions.ReadyToTest()])


@pytest.mark.launch(fixture=launch_description)
def test_read_stdout(hello_world_proc, launch_context):
    def validate_output(output):
        assert output.splitlines() == ["hello_world"], "process never printed hello_world"

    process_tools.assert_output_sync(launch_context, hello_world_proc, validate_output, timeout=30)

    def never(output):
        return output == "this will never happen"

    assert not process_tools.wait_for_output_sync(launch_context, hello_world_proc, never, timeout=0.1)
    # the launch shuts down after the yield, and SIGINTs an echo that has printed but not yet exited
    assert process_tools.wait_for_exit_sync(launch_context, hello_world_proc, timeout=10)
    yield
    assert hello_world_proc.return_code == 0


@pytest.fixture
def counter():
    code = "import time\nfor i in range(100):\n    print('tick', i, flush=True)\n    time.sleep(0.05)\n"
    return launch.actions.ExecuteProcess(cmd=[sys.executable, "-c", code], cached_output=True, name="counter")


@launch_pytest.fixture
def counting(counter):
    return launch.LaunchDescription([counter])


@pytest.mark.launch(fixture=counting)
async def test_async_output(counter, launch_context):
    assert await process_tools.wait_for_output(launch_context, counter, lambda out: "tick 3" in out, timeout=10)


@pytest.mark.launch(fixture=counting, shutdown=True)
def test_after_shutdown(counter, launch_service):
    assert launch_service.event_loop is None  # the launch is over
    assert counter.return_code is not None  # interrupted by the shutdown (wherever it was in its start-up)


@pytest.mark.launch(fixture=counting)
def test_fails_on_purpose(counter, launch_context):
    process_tools.assert_output_sync(launch_context, counter, lambda out: _expect("tock", out), timeout=0.3)


def _expect(text, out):
    assert text in out, f"{text!r} not in the output"


@launch_pytest.fixture
def talker_launch():
    import os

    here = os.path.dirname(os.path.abspath(__file__))
    return launch.LaunchDescription([
        launch.actions.ExecuteProcess(cmd=[sys.executable, os.path.join(here, "talker.py")], name="talker"),
    ])


@pytest.mark.launch(fixture=talker_launch)
def test_check_if_msgs_published():
    import threading

    import rclpy
    from std_msgs.msg import String

    rclpy.init()
    try:
        node = rclpy.create_node("test_node")
        got = threading.Event()
        node.create_subscription(String, "chatter", lambda msg: got.set(), 10)
        deadline = __import__("time").monotonic() + 10
        while not got.is_set() and __import__("time").monotonic() < deadline:
            rclpy.spin_once(node, timeout_sec=0.1)
        assert got.is_set(), "Did not receive msgs !"
        node.destroy_node()
    finally:
        rclpy.shutdown()
