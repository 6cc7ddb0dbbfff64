"""sensor_msgs_py.point_cloud2 as upstream's (common_interfaces, Jazzy) behaves with the real message classes:
reading clouds as structured arrays, lists and plain arrays (field selection, NaNs, uv indices, organized
clouds), dtypes from PointFields, creating clouds, and its assertion messages. The expected outputs
(data/point_cloud2_jazzy.json) are upstream's own, made by make_runtime_golden.py."""

from __future__ import annotations

import json
from pathlib import Path

from tests.interfaces.point_cloud2_program import PROGRAM
from tests.interfaces.programs import assert_same, run_ours

GOLDEN = Path(__file__).parent / "data" / "point_cloud2_jazzy.json"


def test_point_cloud2_as_upstream() -> None:
    assert_same(run_ours(PROGRAM), json.loads(GOLDEN.read_text()))
