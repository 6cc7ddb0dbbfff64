"""interactive_marker_twist_server's marker_server as a real process on a real router, driven as RViz drives it:
the markers fetched from twist_server/get_interactive_markers (planar.yaml: move_x, move_y, rotate_z), a drag sent
on twist_server/feedback turning into a Twist (marker_server.cpp's scales and limits: 2.2 × yaw within ±2.2,
linear_scale × displacement within the velocity limits) and the marker snapped back in an update; a second
client's feedback within a second is ignored, as interactive_markers' server ignores it."""

from __future__ import annotations

import math
import threading
from typing import Any

import pytest

from diffctl.interactive_marker_twist_server.twist_from_pose import DEFAULT, Scales, twist
from tests.probe import call, probe
from tests.waiting import wait_for

PLANAR = Scales({"x": 1.0, "y": 1.0}, {"x": 1.0, "y": 1.0}, {"x": -1.0, "y": -1.0})


def yaw(angle: float) -> tuple[float, float, float, float]:
    return 0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2)


def test_twist_rule() -> None:
    assert twist(PLANAR, (0.5, -2.0, 3.0), yaw(0.3)) == (pytest.approx((0.5, -1.0, 0.0)), pytest.approx(0.66))
    assert twist(DEFAULT, (2.0, 1.0, 0.0), yaw(-2.0))[1] == -2.2  # clamped
    assert twist(Scales({"x": 2.0}, {}, {}), (0.5, 0, 0), yaw(0))[0][0] == 0.0  # no limits: clamped to 0


@pytest.mark.slow
def test_drag_sends_twist_and_snaps_back(router: str, procs, tmp_path) -> None:
    from diffctl.workspace.package_index import share_dir

    config = share_dir("interactive_marker_twist_server") / "config" / "planar.yaml"
    node = procs.diffctl("run", "interactive_marker_twist_server", "marker_server", "--ros-args", "--params-file",
                         str(config))
    p = probe("rviz_probe")
    lock = threading.Lock()
    got: dict[str, list[Any]] = {"cmd": [], "update": []}

    def keep(key: str):
        def on(m: Any) -> None:
            with lock:
                got[key].append(m)
        return on

    try:
        p.create_subscription("/cmd_vel", "geometry_msgs/msg/Twist", keep("cmd"))
        p.create_subscription("/twist_server/update", "visualization_msgs/msg/InteractiveMarkerUpdate",
                              keep("update"), depth=100)
        markers = call(p, "/twist_server/get_interactive_markers", "visualization_msgs/srv/GetInteractiveMarkers",
                       timeout_s=60)
        (m,) = markers.markers
        assert (m.name, m.header.frame_id, markers.sequence_number) == ("robot_twist_marker", "base_link", 1)
        assert [(c.name, c.interaction_mode) for c in m.controls] == [("move_x", 3), ("move_y", 3), ("rotate_z", 5)]
        feedback = p.create_publisher("/twist_server/feedback", "visualization_msgs/msg/InteractiveMarkerFeedback",
                                      depth=1)
        assert wait_for(lambda: feedback.subscription_count > 0, timeout_s=30)
        x, y, z, w = yaw(0.3)
        drag = {"client_id": "/rviz/InteractiveMarkers", "marker_name": "robot_twist_marker", "event_type": 1,
                "pose": {"position": {"x": 0.5, "y": -2.0}, "orientation": {"x": x, "y": y, "z": z, "w": w}}}
        feedback.publish(drag)
        assert wait_for(lambda: bool(got["cmd"]), timeout_s=30)
        cmd = got["cmd"][0]
        assert (cmd.linear.x, cmd.linear.y, cmd.angular.z) == (pytest.approx(0.5), -1.0, pytest.approx(0.66))
        assert wait_for(lambda: any(u.poses for u in got["update"]), timeout_s=30)
        snapped = next(u for u in got["update"] if u.poses)
        assert snapped.seq_num == 2 and snapped.poses[0].pose.position.x == 0.0
        assert snapped.poses[0].header.frame_id == "base_link"
        feedback.publish({**drag, "client_id": "/other_rviz"})  # a second client, within the second
        feedback.publish(drag)
        assert wait_for(lambda: len(got["cmd"]) >= 2, timeout_s=30)
        assert len(got["cmd"]) == 2
    finally:
        p.close()
    assert procs.stop(node) == 0
