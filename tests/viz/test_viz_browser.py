"""The page in real headless Chromium: offline, draws the robot, drives it with the arrow keys, refuses
a wrong token. Screenshots land in test-output/viz/ for a person to look at."""

from __future__ import annotations

import shutil
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.probe import Probe
from tests.viz.recorder import Recorder

REPO = Path(__file__).resolve().parents[2]
SHOTS = REPO / "test-output" / "viz"
CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
CHROMIUM_FLAGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
CMD_TOPIC = "/diffbot_base_controller/cmd_vel"

pytestmark = [pytest.mark.browser, pytest.mark.slow]


@pytest.fixture
def browser(tmp_path: Path) -> Iterator[object]:
    """A fresh headless Chromium context (new empty profile); closed, with its processes, at teardown."""
    if not Path(CHROMIUM).exists():
        pytest.fail("Debian's chromium is not installed: `make system-deps` (or apt-get install chromium)")
    from playwright.sync_api import sync_playwright

    with sync_playwright() as pw:
        ctx = pw.chromium.launch_persistent_context(
            str(tmp_path / "profile"),
            executable_path=CHROMIUM,
            headless=True,
            args=CHROMIUM_FLAGS,
            viewport={"width": 1280, "height": 800},
        )
        try:
            yield ctx
        finally:
            ctx.close()


def open_page(ctx, url: str, requests: list[str]):
    page = ctx.new_page()
    page.on("request", lambda r: requests.append(r.url))
    page.goto(url)
    page.wait_for_function("() => window.diffviz && window.diffviz.connected && window.diffviz.hello", timeout=15000)
    return page


def test_page_offline_draws_robot_and_arrow_up_drives_it(fake_robot, start_viz, browser) -> None:
    viz = start_viz("-d", str(REPO / "config" / "diffbot.rviz"))  # as the tutorial's launch file passes it
    node = Probe("viz_browser_test")
    cmds = Recorder(node, CMD_TOPIC, "geometry_msgs/msg/TwistStamped")
    odom = Recorder(node, "/diffbot_base_controller/odom", "nav_msgs/msg/Odometry")
    requests: list[str] = []
    page = open_page(browser, viz.url, requests)
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))

    # The robot model, the scan and the odometry arrive and are drawn.
    page.wait_for_function(
        "() => diffviz.stats.robotPolygonsDrawn >= 7 && diffviz.stats.scanPointsDrawn >= 300", timeout=15000
    )
    assert page.evaluate("diffviz.authorized") is True
    # Pixels, not only JS state: the chassis' colour (SDF diffuse 0.1 0.3 0.8) is on the canvas where the
    # chassis box is (base_link + (-0.21, -0.06) m: inside the box, clear of the other links and TF axes).
    rgb = page.evaluate("""() => {
        const t = diffviz.frame.frames.base_link, dpr = window.devicePixelRatio || 1;
        const c = Math.cos(t[3]), s = Math.sin(t[3]);
        const [x, y] = diffviz.toScreen(t[0] - 0.21 * c + 0.06 * s, t[1] - 0.21 * s - 0.06 * c);
        return Array.from(document.getElementById('canvas').getContext('2d')
            .getImageData(Math.round(x * dpr), Math.round(y * dpr), 1, 1).data).slice(0, 3);
    }""")
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / "viz_robot.png"))
    assert abs(rgb[0] - 26) <= 30 and abs(rgb[1] - 77) <= 30 and abs(rgb[2] - 204) <= 30, rgb

    x_before = odom.snapshot()[-1].pose.pose.position.x
    page.locator("#canvas").click()
    page.keyboard.down("ArrowUp")
    time.sleep(1.5)
    page.keyboard.up("ArrowUp")
    page.wait_for_function("() => diffviz.teleop.linear === 0")
    time.sleep(0.5)

    # Checked on the bus: the page published TwistStamped forward while the key was held, then a zero.
    seen = cmds.snapshot()
    forward = [m for m in seen if m.twist.linear.x > 0]
    assert len(forward) >= 10, [m.twist.linear.x for m in seen]  # 10 Hz while held
    assert all(abs(m.twist.linear.x - 0.5) < 1e-9 and m.twist.angular.z == 0 for m in forward)
    assert seen[-1].twist.linear.x == 0.0
    x_after = odom.snapshot()[-1].pose.pose.position.x
    assert x_after - x_before > 0.5, (x_before, x_after)  # ~0.75 m at 0.5 m/s for 1.5 s

    # The on-screen joystick: dragged up and to the left → forward and turning left; let go → zero.
    n0 = len(cmds.snapshot())
    box = page.locator("#joystick").bounding_box()
    cx, cy = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(cx, cy)
    page.mouse.down()
    page.mouse.move(cx - 20, cy - 40, steps=5)  # full deflection is 50 px (radius 70 minus the knob's margin)
    time.sleep(0.5)
    page.mouse.up()
    time.sleep(0.3)
    joy = cmds.snapshot()[n0:]
    held = [m for m in joy if m.twist.linear.x > 0]
    # 40 px up of 50 → 0.8 of the 0.5 m/s slider; 20 px left of 50 → 0.4 of the 1 rad/s slider.
    assert len(held) >= 4
    assert all(abs(m.twist.linear.x - 0.4) < 1e-9 and abs(m.twist.angular.z - 0.4) < 1e-9 for m in held[-3:])
    assert joy[-1].twist.linear.x == 0 and joy[-1].twist.angular.z == 0

    # A game pad through the browser's Gamepad API: left stick forward, then back inside the dead zone.
    n0 = len(cmds.snapshot())
    page.evaluate("""() => {
        window.fakePad = {id: 'test pad', connected: true, axes: [0, -1, 0, 0], buttons: []};
        Object.defineProperty(navigator, 'getGamepads', {value: () => [window.fakePad], configurable: true});
    }""")
    time.sleep(0.6)
    page.evaluate("window.fakePad.axes = [0.1, -0.1, 0, 0]")  # within the 0.15 dead zone
    time.sleep(0.3)
    pad = cmds.snapshot()[n0:]
    assert [m.twist.linear.x for m in pad].count(0.5) >= 4 and pad[-1].twist.linear.x == 0
    assert page.inner_text("#gamepad") == "game pad: test pad"

    # Fixed frame chosen in the page: in base_footprint the robot sits at the origin and odom lies behind it.
    page.select_option("#fixed-frame", "base_footprint")
    page.wait_for_function("() => diffviz.frame && diffviz.frame.fixed === 'base_footprint'")
    fp = page.evaluate("[diffviz.frame.frames.base_footprint, diffviz.frame.frames.odom]")
    assert fp[0][:2] == [0, 0] and fp[1][0] < -0.5
    page.select_option("#fixed-frame", "odom")
    page.wait_for_function("() => diffviz.frame && diffviz.frame.fixed === 'odom'")

    # Open the other panels for the screenshot; the camera subscribes only now and shows the fake image.
    for panel in ("panel-camera", "panel-joints", "panel-topics", "panel-controllers"):
        page.evaluate(f"document.getElementById('{panel}').open = true")
    page.wait_for_function("() => document.getElementById('camera-img').naturalWidth === 64", timeout=10000)
    page.wait_for_function("() => document.querySelectorAll('#topics tbody tr').length >= 5", timeout=5000)
    page.wait_for_function("() => document.querySelectorAll('#joints tbody tr').length === 2", timeout=5000)
    page.check("#follow")
    page.evaluate("diffviz.view.scale = 300 * (window.devicePixelRatio || 1); diffviz.dirty = true")
    time.sleep(0.3)
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / "viz_after_drive.png"))

    foreign = [u for u in requests if not (u.startswith(viz.base) or u.startswith("data:"))]
    assert foreign == [], foreign  # self-contained: nothing but the visualizer itself is ever asked for
    assert errors == []
    node.close()


def test_wrong_token_is_refused_with_a_visible_message(viz, browser) -> None:
    node = Probe("viz_browser_test")
    cmds = Recorder(node, CMD_TOPIC, "geometry_msgs/msg/TwistStamped")
    page = open_page(browser, f"{viz.base}/?token=not-the-token", [])
    assert page.evaluate("diffviz.authorized") is False
    assert page.locator("#auth").inner_text() == "view only"
    page.locator("#canvas").click()
    page.keyboard.down("ArrowUp")
    page.wait_for_function("() => diffviz.refused.length > 0", timeout=5000)
    page.keyboard.up("ArrowUp")
    notice = page.locator("#notices .notice.refused").first
    assert notice.is_visible() and "token" in notice.inner_text()
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / "viz_wrong_token.png"))
    # The right token typed into the page unlocks it.
    page.fill("#token-input", viz.token)
    page.click("#token-send")
    page.wait_for_function("() => diffviz.authorized === true", timeout=5000)
    time.sleep(0.3)
    assert cmds.snapshot() == []

    # Now unlocked: the Message Publisher panel, first with a bad field (shown, nothing sent), then good.
    strings = Recorder(node, "/viz_test/chatter", "std_msgs/msg/String")
    page.evaluate("document.getElementById('panel-publisher').open = true")
    page.fill("#pub-topic", "/viz_test/chatter")
    page.fill("#pub-type", "std_msgs/msg/String")
    page.fill("#pub-body", "datum: hello")
    page.click("#pub-send")
    page.wait_for_function("() => document.getElementById('pub-status').className === 'err'", timeout=5000)
    assert "unknown field 'datum'" in page.inner_text("#pub-status")
    page.click("#pub-template")
    page.wait_for_function("() => document.getElementById('pub-body').value.startsWith('data:')", timeout=5000)
    page.fill("#pub-body", "data: hello from the page")
    page.click("#pub-send")
    page.wait_for_function("() => document.getElementById('pub-status').textContent.startsWith('published')")
    time.sleep(0.3)
    assert [m.data for m in strings.snapshot()] == ["hello from the page"]
    node.close()


def test_full_sim_control_stack_driven_from_the_page(launch_sim_control, browser) -> None:
    """`diffctl launch sim_control` as the tutorial runs it: the page it starts drives the simulated car."""
    viz = launch_sim_control()
    node = Probe("viz_browser_test")
    odom = Recorder(node, "/diffbot_base_controller/odom", "nav_msgs/msg/Odometry")
    page = open_page(browser, viz.url, [])
    # The empty world gives the lidar nothing to hit: the scan arrives, with no points to draw.
    page.wait_for_function(
        "() => diffviz.stats.robotPolygonsDrawn >= 7 && diffviz.scans['/scan'] "
        "&& diffviz.frame && diffviz.frame.gt && diffviz.status && diffviz.status.rtf",
        timeout=20000,
    )
    assert page.evaluate("diffviz.status.rtf_source") == "sim stats"
    page.wait_for_function(
        "() => diffviz.graph && diffviz.graph.controllers && diffviz.graph.controllers.length === 2"
        " && diffviz.graph.controllers.every(c => c.state === 'active')",
        timeout=10000,
    )
    x0 = odom.snapshot()[-1].pose.pose.position.x
    page.locator("#canvas").click()
    page.keyboard.down("ArrowUp")
    page.keyboard.down("ArrowLeft")
    time.sleep(2.0)
    page.keyboard.up("ArrowLeft")
    page.keyboard.up("ArrowUp")
    # Released: the page's zero command brakes the car through the controller's 1 m/s² limit (0.5 s from
    # 0.5 m/s, plus however long this loaded machine takes to deliver the key-up).
    deadline = time.monotonic() + 5.0
    while abs(odom.snapshot()[-1].twist.twist.linear.x) >= 0.05 and time.monotonic() < deadline:
        time.sleep(0.05)
    last = odom.snapshot()[-1]
    # diff_drive_controller's acceleration limits make the start gentle; the car still covers a good part
    # of 0.5 m/s × 2 s, turning left (positive yaw) as asked.
    assert last.pose.pose.position.x - x0 > 0.25, (x0, last.pose.pose.position.x)
    assert last.pose.pose.orientation.z > 0.1
    assert abs(last.twist.twist.linear.x) < 0.05  # released: the zero command stopped it
    # Ground truth (the simulator's) and odometry (the controller's) agree on where the car went.
    gt = page.evaluate("diffviz.frame.gt")
    pose = page.evaluate("diffviz.frame.odom.find(o => o.topic === '/diffbot_base_controller/odom').pose")
    assert abs(gt[0] - pose[0]) < 0.05 and abs(gt[1] - pose[1]) < 0.05
    for panel in ("panel-controllers", "panel-joints", "panel-camera"):
        page.evaluate(f"document.getElementById('{panel}').open = true")
    page.wait_for_function("() => document.getElementById('camera-img').naturalWidth > 0", timeout=15000)
    page.evaluate("diffviz.view.scale = 250 * (window.devicePixelRatio || 1); diffviz.dirty = true")
    page.check("#follow")
    time.sleep(0.5)
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / "viz_sim_control.png"))
    node.close()
