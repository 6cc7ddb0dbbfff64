"""ekf_node on the simulated tutorial car: `Node(package='robot_localization', executable='ekf_node')` in a
launch file beside the simulator, fusing the diff drive controller's odometry and the IMU's yaw rate while
the car drives an arc. The filtered pose is checked against the simulator's ground truth and against the
unicycle model of the commanded arc."""

from __future__ import annotations

import math
import threading
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import free_port
from tests.e2e.stack import Sample, Stack, yaw_of

pytestmark = pytest.mark.slow
LAUNCH = Path(__file__).parent / "data" / "ekf_car.launch.py"
CMD = "/diffbot_base_controller/cmd_vel"
V, W = 0.4, 0.4  # m/s, rad/s: an arc of 1 m radius
SEC = 1_000_000_000


@pytest.fixture
def stack_env(monkeypatch: pytest.MonkeyPatch):
    """The launch's own router on a free port (the launch embeds it), this test's session pointed at it."""
    from diffctl.bus.session import close_session

    endpoint = f"tcp/127.0.0.1:{free_port()}"
    monkeypatch.setenv("DIFFCTL_ROUTER", endpoint)
    yield endpoint
    close_session()


def test_ekf_tracks_the_car_along_an_arc(stack_env: str, tmp_path: Path) -> None:
    stack = Stack(str(LAUNCH), tmp_path, rtf="2")
    filtered: list[Sample] = []
    lock = threading.Lock()
    try:
        node = stack.connect()
        stack.watch_odom("/diffbot_base_controller/odom")

        def on_filtered(m: Any) -> None:
            p = m.pose.pose
            with lock:
                filtered.append(Sample(m.header.stamp.sec * SEC + m.header.stamp.nanosec,
                                       (p.position.x, p.position.y, yaw_of(p.orientation))))

        node.create_subscription("/odometry/filtered", "nav_msgs/msg/Odometry", on_filtered)
        stack.wait_controllers_active(("diffbot_base_controller", "joint_state_broadcaster"))
        w = stack.watch
        stack.wait_sim(stack.clock_ns + SEC // 2)
        stack.wait_truth(stack.clock_ns)
        stack.command(CMD, "geometry_msgs/msg/TwistStamped", {"twist": {"linear": {"x": V}, "angular": {"z": W}}})
        start_ns = stack.clock_ns
        stack.wait_sim(start_ns + 9 * SEC)
        end_ns = stack.clock_ns
        stack.command(CMD, "geometry_msgs/msg/TwistStamped", None)
        stack.wait_truth(end_ns)
        with lock:
            fused = [s for s in filtered if start_ns - SEC <= s.t_ns <= end_ns]
        assert len(fused) > 100, f"only {len(fused)} filtered poses in 10 s of sim time"

        def nearest(series: list[Sample], t_ns: int) -> Sample:
            return min(series, key=lambda s: abs(s.t_ns - t_ns))

        # The filter and the simulator start from the same pose (the spawn point, yaw 0): compare the motion
        # since the first filtered pose, at every second of the drive.
        f0 = fused[0]
        g0 = w.at(w.truth, f0.t_ns)
        worst_pos = worst_yaw = 0.0
        for k in range(1, 10):
            t = start_ns + k * SEC
            f, g = nearest(fused, t), w.at(w.truth, t)
            assert abs(f.t_ns - g.t_ns) < SEC // 10
            dx, dy = f.value[0] - f0.value[0], f.value[1] - f0.value[1]
            gx, gy = g.value[0] - g0.value[0], g.value[1] - g0.value[1]
            worst_pos = max(worst_pos, math.hypot(dx - gx, dy - gy))
            worst_yaw = max(worst_yaw, abs(math.remainder((f.value[2] - f0.value[2]) - (g.value[2] - g0.value[2]),
                                                          math.tau)))
        assert worst_pos < 0.05, f"filtered position up to {worst_pos:.3f} m from the ground truth"
        assert worst_yaw < 0.03, f"filtered yaw up to {worst_yaw:.4f} rad from the ground truth"

        # Steady on the arc (past the 1 m/s², 1 rad/s² ramps): over 4 s the unicycle model turns W·4 rad and
        # moves along a chord of 2·(V/W)·sin(W·2); the filter must agree within 3 %.
        a, b = nearest(fused, start_ns + 3 * SEC), nearest(fused, start_ns + 7 * SEC)
        span = (b.t_ns - a.t_ns) / SEC
        turned = math.remainder(b.value[2] - a.value[2], math.tau)
        chord = math.hypot(b.value[0] - a.value[0], b.value[1] - a.value[1])
        assert turned == pytest.approx(W * span, rel=0.03), (turned, W * span)
        assert chord == pytest.approx(2 * (V / W) * math.sin(W * span / 2), rel=0.03), chord
        print(f"EKF vs ground truth: position {worst_pos * 1000:.1f} mm, yaw {worst_yaw * 1000:.2f} mrad; "
              f"arc: turned {turned:.4f} rad (model {W * span:.4f}), chord {chord:.4f} m "
              f"(model {2 * (V / W) * math.sin(W * span / 2):.4f})")
    finally:
        stack.kill()
