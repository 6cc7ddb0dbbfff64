"""joint_state_publisher_gui's counterpart in real headless Chromium: the visualizer's Joint Sliders panel
offers the robot's movable joints with their ranges, and moving one publishes a JointState on /joint_sliders,
which the launch's joint_state_publisher_gui (diffctl's joint_state_publisher, source_list) merges."""

from __future__ import annotations

import time

import pytest

from diffctl.workspace.gui_tools import argv_for
from tests.probe import Probe
from tests.viz.conftest import fake_robot, start_viz  # noqa: F401 (fixtures)
from tests.viz.recorder import Recorder
from tests.viz.test_viz_browser import browser, open_page  # noqa: F401 (fixture)

pytestmark = [pytest.mark.browser, pytest.mark.slow]


def test_joint_sliders_publish_what_joint_state_publisher_gui_would(fake_robot, start_viz, browser) -> None:  # noqa: F811
    assert "source_list:=[/joint_sliders]" in argv_for("joint_state_publisher_gui", "joint_state_publisher_gui")[-1]
    viz = start_viz()
    node = Probe("sliders_browser_test")
    sliders = Recorder(node, "/joint_sliders", "sensor_msgs/msg/JointState")
    page = open_page(browser, viz.url, [])
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.evaluate("document.getElementById('panel-sliders').open = true")
    page.wait_for_function("() => document.querySelectorAll('#sliders input').length >= 2", timeout=15000)
    joints = page.evaluate(
        "Array.from(document.querySelectorAll('#sliders input')).map(i => [i.dataset.joint, +i.min, +i.max])"
    )
    # the tutorial car's wheels are continuous joints: ±π, as joint_state_publisher_gui offers them
    assert all(abs(lo + 3.14159) < 1e-3 and abs(hi - 3.14159) < 1e-3 for _, lo, hi in joints), joints
    first = joints[0][0]
    page.evaluate(
        "() => { const i = document.querySelector('#sliders input');"
        " i.value = 1.25; i.dispatchEvent(new Event('input')); }"
    )
    deadline = time.monotonic() + 10
    while not sliders.snapshot() and time.monotonic() < deadline:
        time.sleep(0.05)
    assert sliders.snapshot(), page.inner_text("#sliders-status") + str(errors) + str(page.evaluate("diffviz.refused"))
    msg = sliders.snapshot()[-1]
    assert list(msg.name) == [j for j, _, _ in joints]
    assert abs(msg.position[0] - 1.25) < 0.01 and list(msg.position[1:]) == [0.0] * (len(joints) - 1)
    assert first == msg.name[0]
    assert errors == []
    node.close()
