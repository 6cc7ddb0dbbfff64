"""Pure math of the visualizer: transforms, the TF buffer, top-down outlines, the robot model placement."""

from __future__ import annotations

import math
from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

from diffctl.viz.footprint import Primitive, convex_hull, outline, polygon_area_m2
from diffctl.viz.robot_model import parse_description
from diffctl.viz.transforms import IDENTITY, TfBuffer, Transform, quat_from_rpy

REPO = Path(__file__).resolve().parents[2]
angle = st.floats(-math.pi, math.pi)
coord = st.floats(-50, 50)
transforms = st.builds(Transform.from_xyz_rpy, coord, coord, coord, angle, angle, angle)


def close(a: Transform, b: Transform, tol: float = 1e-9) -> bool:
    dq = sum(x * y for x, y in zip(a.rotation, b.rotation, strict=True))
    return (
        all(abs(x - y) < tol for x, y in zip(a.translation_m, b.translation_m, strict=True)) and abs(abs(dq) - 1) < tol
    )


@settings(max_examples=200, deadline=None)
@given(transforms, transforms, st.tuples(coord, coord, coord))
def test_compose_inverse_and_apply_agree(a: Transform, b: Transform, p) -> None:
    assert close(a.compose(a.inverse()), IDENTITY)
    ab = a.compose(b)
    direct = ab.apply(p)
    stepwise = a.apply(b.apply(p))
    assert all(abs(x - y) < 1e-9 for x, y in zip(direct, stepwise, strict=True))
    m = ab.rotation_matrix()
    rotated = [sum(m[i][j] * p[j] for j in range(3)) + ab.translation_m[i] for i in range(3)]
    assert all(abs(x - y) < 1e-9 for x, y in zip(rotated, direct, strict=True))


def test_tf_buffer_lookup_across_branches_and_its_guards() -> None:
    tf = TfBuffer()
    tf.set("odom", "base_footprint", Transform.from_xyz_rpy(1.0, 2.0, 0.0, yaw=math.pi / 2))
    tf.set("base_footprint", "base_link", Transform((0.0, 0.0, 0.04)), static=True)
    tf.set("base_link", "left_wheel", Transform((0.0, 0.15, 0.0)), static=True)
    tf.set("/base_link", "/lidar_link", Transform((-0.05, 0.0, 0.075)), static=True)  # old-style names
    # The wheel in odom: base turned 90° left, so the wheel's +0.15 m in y lies at −0.15 m in odom's x.
    w = tf.lookup("odom", "left_wheel")
    assert w is not None and all(abs(a - b) < 1e-12 for a, b in zip(w.translation_m, (0.85, 2.0, 0.04), strict=True))
    # Between two leaves: lidar seen from the wheel.
    lw = tf.lookup("left_wheel", "lidar_link")
    assert lw is not None and all(
        abs(a - b) < 1e-12 for a, b in zip(lw.translation_m, (-0.05, -0.15, 0.075), strict=True)
    )
    assert tf.lookup("odom", "map") is None  # not connected
    assert set(tf.all_in("base_link")) == {"odom", "base_footprint", "base_link", "left_wheel", "lidar_link"}
    assert not tf.set("left_wheel", "odom", IDENTITY)  # would close a cycle
    assert not tf.set("odom", "x", Transform((math.nan, 0.0, 0.0)))  # non-finite never enters the tree
    assert not tf.set("base_footprint", "base_link", IDENTITY)  # /tf cannot override a /tf_static edge
    tf.clear_dynamic()  # a jump back in sim time: static edges stay
    assert tf.lookup("odom", "base_link") is None and tf.lookup("base_link", "lidar_link") is not None


def test_outlines_of_primitives() -> None:
    # A 0.3 × 0.2 box yawed 90°: 0.2 wide in x, 0.3 in y, top at centre + half height.
    box = outline(Primitive("box", size_m=(0.3, 0.2, 0.05)), Transform.from_xyz_rpy(1, 0, 0.1, yaw=math.pi / 2))
    xs, ys = [p[0] for p in box.points_xy_m], [p[1] for p in box.points_xy_m]
    assert (round(min(xs), 9), round(max(xs), 9), round(min(ys), 9), round(max(ys), 9)) == (0.9, 1.1, -0.15, 0.15)
    assert abs(box.top_z_m - 0.125) < 1e-12 and abs(polygon_area_m2(box.points_xy_m) - 0.06) < 1e-12
    # A wheel: cylinder r 0.04, length 0.02 turned onto the y axis (roll −90°) → a 0.08 × 0.02 rectangle.
    wheel = outline(
        Primitive("cylinder", radius_m=0.04, length_m=0.02), Transform((0, 0, 0.04), quat_from_rpy(-math.pi / 2, 0, 0))
    )
    xs, ys = [p[0] for p in wheel.points_xy_m], [p[1] for p in wheel.points_xy_m]
    assert abs(max(xs) - 0.04) < 1e-9 and abs(min(xs) + 0.04) < 1e-9 and abs(max(ys) - 0.01) < 1e-9
    assert abs(wheel.top_z_m - 0.08) < 1e-9
    # Upright cylinder: a 16-gon inscribed in the circle.
    disc = outline(Primitive("cylinder", radius_m=1.0, length_m=1.0), IDENTITY)
    assert (
        len(disc.points_xy_m) == 16 and abs(polygon_area_m2(disc.points_xy_m) - 8 * math.sin(2 * math.pi / 16)) < 1e-9
    )
    cap = outline(
        Primitive("capsule", radius_m=0.1, length_m=1.0), Transform((0, 0, 0), quat_from_rpy(0, math.pi / 2, 0))
    )
    assert abs(max(p[0] for p in cap.points_xy_m) - 0.6) < 1e-9
    assert outline(Primitive("mesh"), IDENTITY) is None
    assert convex_hull([(0, 0), (1, 0), (1, 1), (0, 1), (0.5, 0.5), (0.5, 0)]) == [(0, 0), (1, 0), (1, 1), (0, 1)]


def test_robot_model_from_the_repo_sdf_placed_from_partial_tf() -> None:
    robot = parse_description((REPO / "description" / "my_diff_car_control.sdf").read_text())
    assert {"base_link", "left_wheel", "right_wheel", "caster", "lidar_link"} <= set(robot.links)
    # Only odom→base_footprint known (no robot_state_publisher yet): every link still gets placed.
    at = Transform.from_xyz_rpy(2.0, 1.0, 0.0, yaw=math.pi)
    placed = robot.place({"base_footprint": at})
    assert set(placed) == set(robot.links)
    left = placed["left_wheel"]  # +0.15 m left of base_link, turned 180° → at x 2, y 0.85
    assert abs(left.translation_m[0] - 2.0) < 1e-9 and abs(left.translation_m[1] - 0.85) < 1e-9
    # A link TF knows wins over the rest pose.
    moved = robot.place({"base_footprint": at, "left_wheel": IDENTITY})
    assert moved["left_wheel"] == IDENTITY and moved["right_wheel"] == placed["right_wheel"]
    drawn = robot.outlines({"base_footprint": at})
    assert [s.link for s, _ in drawn][-1] == "lidar_link"  # highest on top
    chassis = next(o for s, o in drawn if s.link == "base_link")
    assert abs(polygon_area_m2(chassis.points_xy_m) - 0.3 * 0.2) < 1e-9
