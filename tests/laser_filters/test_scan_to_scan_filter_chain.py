"""scan_to_scan_filter_chain as a real process on a real router, with a Husarion-style chain (`/**/` key, a box
around the robot in base_link, then a range filter): the laser's readings inside the box go, far ones are
replaced; the filter parameters are declared read-only with their types; a chain naming a filter that is not
provided, or a filterN.name without its type, is refused (exit 2)."""

from __future__ import annotations

import math
import subprocess
import sys
import threading
from pathlib import Path
from typing import Any

import pytest

from tests.probe import parameters, probe
from tests.waiting import wait_for

pytestmark = pytest.mark.slow

CHAIN = """/**/scan_to_scan_filter_chain:
  ros__parameters:
    filter1:
      name: box_filter
      type: laser_filters/LaserScanBoxFilter
      params:
        box_frame: base_link
        max_x: 0.165
        min_x: -0.195
        max_y: 0.145
        min_y: -0.145
        max_z: 0.5
        min_z: -0.5
        invert: false
    filter2:
      name: far
      type: laser_filters/LaserScanRangeFilter
      params:
        lower_threshold: 0.0
        upper_threshold: 2.0
        upper_replacement_value: .inf
"""


def test_box_and_range_chain(router: str, procs, tmp_path: Path) -> None:
    (tmp_path / "laser_filter.yaml").write_text(CHAIN)
    node = procs.diffctl("run", "laser_filters", "scan_to_scan_filter_chain", "--ros-args", "--params-file",
                         str(tmp_path / "laser_filter.yaml"))
    p = probe("laser_probe")
    got: list[Any] = []
    lock = threading.Lock()

    def on(m: Any) -> None:
        with lock:
            got.append(m)

    try:
        p.create_subscription("/scan_filtered", "sensor_msgs/msg/LaserScan", on)
        # the laser 0.1 m behind base_link's origin, looking backwards
        tf = p.create_publisher("/tf_static", "tf2_msgs/msg/TFMessage", latched=True)
        tf.publish({"transforms": [{"header": {"frame_id": "base_link"}, "child_frame_id": "laser",
                                    "transform": {"translation": {"x": -0.1},
                                                  "rotation": {"z": 1.0, "w": 0.0}}}]})
        scan = p.create_publisher("/scan", "sensor_msgs/msg/LaserScan", reliable=False, depth=5)
        assert wait_for(lambda: scan.subscription_count > 0, timeout_s=60), (procs.stop(node), node.stdout.read())
        # The laser's readings land at base_link (-0.1 - r, 0) straight ahead of it, (-0.1, -r) at 90°: 0.05 m
        # ahead is inside the box (x > -0.195), 0.2 m beyond its back, 3 m far (replaced by inf); 0.1 m at 90°
        # is inside (y > -0.145), 0.2 m beside it.
        straight = {"header": {"frame_id": "laser", "stamp": {"sec": 1}}, "angle_min": 0.0, "angle_max": 0.0,
                    "angle_increment": 0.0, "range_min": 0.01, "range_max": 10.0, "ranges": [0.05, 0.2, 3.0]}
        turned = dict(straight, angle_min=math.pi / 2, angle_max=math.pi / 2, ranges=[0.1, 0.2])
        assert wait_for(lambda: {len(m.ranges) for m in list(got)} >= {2, 3}, timeout_s=60,
                        every=lambda: (scan.publish(straight), scan.publish(turned)))
        with lock:
            ahead = next(list(m.ranges) for m in got if len(m.ranges) == 3)
            beside = next(list(m.ranges) for m in got if len(m.ranges) == 2)
        assert math.isnan(ahead[0]) and ahead[1] == pytest.approx(0.2) and ahead[2] == math.inf
        assert math.isnan(beside[0]) and beside[1] == pytest.approx(0.2)
        declared = parameters(p, "/scan_to_scan_filter_chain")
        assert (declared["filter1.name"].read_only, declared["filter1.type"].read_only) == (True, True)
        assert (declared["filter1.params.max_x"].type, declared["filter1.params.max_x"].read_only) == (3, True)
        assert declared["filter2.params.use_message_range_limits"].type == 1
    finally:
        p.close()
    assert procs.stop(node) == 0


@pytest.mark.parametrize(("chain", "message"), [
    ("filter1: {name: shadows, type: laser_filters/ScanShadowsFilter}",
     "Could not load library for laser_filters/ScanShadowsFilter"),
    ("filter1: {name: a}", "filter1.name and filter1.type are required"),
])
def test_bad_chain_is_refused(router: str, tmp_path: Path, chain: str, message: str) -> None:
    (tmp_path / "chain.yaml").write_text(f"scan_to_scan_filter_chain:\n  ros__parameters:\n    {chain}\n")
    r = subprocess.run([sys.executable, "-m", "diffctl", "run", "laser_filters", "scan_to_scan_filter_chain",
                        "--ros-args", "--params-file", str(tmp_path / "chain.yaml")],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and message in " ".join(r.stderr.split()), r.stderr
