"""A module-scoped launch_pytest fixture with two parameters: tests on each launch, shutdown=True ones after the
others, the parts after `yield` once that launch is down, then the next parameter's launch. (As with ROS's
launch_pytest, the module's one LaunchService does not run again once shut down: the second parameter's
description is included but ends at once, so only the order of the tests is checked there.)"""

import launch_pytest
import launch_testing
import pytest

import launch


@pytest.fixture(scope="module")
def order():
    return []


@launch_pytest.fixture(scope="module", params=["one", "two"])
def keep_alive_launch(request):
    return launch.LaunchDescription([launch_testing.util.KeepAliveProc()]), request.param


@pytest.mark.launch(fixture=keep_alive_launch, shutdown=True)
def test_down(order, launch_service, keep_alive_launch):
    order.append(f"down[{keep_alive_launch[1]}]")
    assert launch_service._is_idle() and launch_service.event_loop is None


@pytest.mark.launch(fixture=keep_alive_launch)
def test_up(order, launch_service, keep_alive_launch):
    order.append(f"up[{keep_alive_launch[1]}]")
    if keep_alive_launch[1] == "one":
        assert launch_service.event_loop is not None and not launch_service._is_idle()
    yield
    order.append(f"after[{keep_alive_launch[1]}]")


def test_order(order):
    assert order == ["up[one]", "down[one]", "after[one]", "up[two]", "down[two]", "after[two]"]
