"""Planning PyBullet bodies from SDF: merged links, mass properties, joint frames, and the errors."""

from __future__ import annotations

import math

import numpy as np
import pybullet as pb
import pytest
from sim_helpers import build, ground, sdf_world

from diffctl.description.model import Inertial
from diffctl.description.pose import Pose
from diffctl.description.sdf_loader import parse_model
from diffctl.errors import DescriptionError
from diffctl.sim.body_plan import plan_model
from diffctl.sim.inertia import combine, from_inertial, principal


def test_parallel_axis_combination_of_two_point_like_masses() -> None:
    tiny = Inertial(1.0, Pose(), 1e-6, 0, 0, 1e-6, 0, 1e-6)
    a = from_inertial(tiny, Pose((1.0, 0, 0)))
    b = from_inertial(tiny, Pose((-1.0, 0, 0)))
    mp = combine([a, b])
    assert mp.mass_kg == 2.0 and mp.com_m == (0.0, 0.0, 0.0)
    t = np.array(mp.tensor_kg_m2)
    assert np.diag(t) == pytest.approx([2e-6, 2.0 + 2e-6, 2.0 + 2e-6])


def test_principal_axes_of_a_rotated_rod() -> None:
    rod = Inertial(1.0, Pose(), 0.5, 0, 0, 0.01, 0, 0.5)  # long along y
    mp = from_inertial(rod, Pose.from_xyz_rpy((0, 0, 0), (0, 0, math.pi / 4)))
    frame, diag = principal(mp)
    assert sorted(diag) == pytest.approx([0.01, 0.5, 0.5])
    axis = frame.rotate((1.0, 0.0, 0.0) if diag[0] == pytest.approx(0.01) else (0.0, 1.0, 0.0))
    # The rod's axis, rotated 45° about z, whichever principal axis carries the small moment.
    r = np.array(frame.to_matrix())[:3, :3]
    small = r[:, int(np.argmin(diag))]
    assert abs(abs(small @ np.array([-math.sqrt(0.5), math.sqrt(0.5), 0.0])) - 1) < 1e-9
    assert axis is not None


ARM = """<?xml version="1.0"?><sdf version="1.8"><model name="arm"><pose>1 2 0.5 0 0 0.3</pose>
  <link name="base"><inertial><mass>2</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
    <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision></link>
  <link name="marker"><pose relative_to="base">0 0 0.2 0 0 0</pose></link>
  <joint name="m" type="fixed"><parent>base</parent><child>marker</child></joint>
  <link name="upper"><pose relative_to="base">0.3 0 0 0 0 0</pose>
    <inertial><pose>0.1 0 0 0 0 0</pose><mass>0.5</mass>
      <inertia><ixx>0.001</ixx><iyy>0.002</iyy><izz>0.002</izz></inertia></inertial>
    <collision name="c"><pose>0.1 0 0 0 0 0</pose><geometry><box><size>0.2 0.05 0.05</size></box></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute"><parent>base</parent><child>upper</child>
    <pose>0.05 0 0 0 0 0</pose>
    <axis><xyz>0 0 1</xyz><limit><lower>-0.5</lower><upper>0.5</upper></limit></axis></joint>
</model></sdf>"""


def test_joint_frame_becomes_the_link_frame_and_links_keep_their_sdf_poses() -> None:
    model = parse_model(ARM)
    plan = plan_model(model)
    (body,) = plan.bodies
    assert [lp.members for lp in body.links] == [("base", "marker"), ("upper",)]
    upper = body.links[1]
    # The joint is at 0.05 m along the child link: PyBullet's link frame is there.
    assert upper.frame_world.is_close(model.joint("shoulder").pose_world, 1e-12)
    assert plan.links["upper"].offset.is_close(Pose((-0.05, 0, 0)), 1e-12)
    assert plan.joints == {"shoulder": (0, 0)}
    world = sdf_world(ground())
    from diffctl.sim.world import PhysicsWorld

    pw = PhysicsWorld(world.physics)
    try:
        e = pw.add_model(model)
        for link in model.links:
            assert e.link_pose(link.name).is_close(link.pose_world, 1e-6)  # PyBullet keeps ~1e-7
        # Joint limits from the SDF hold.
        h = e.joint("shoulder")
        pb.setJointMotorControl2(
            h.body, h.index, pb.VELOCITY_CONTROL, targetVelocity=5, force=50, physicsClientId=pw.client
        )
        pb.setGravity(0, 0, 0, physicsClientId=pw.client)
        for _ in range(500):
            pw.step()
        assert e.joint_states([h])[0][0] == pytest.approx(0.5, abs=0.02)
    finally:
        pw.close()


def test_a_moving_link_without_inertial_is_an_error_naming_it() -> None:
    text = ARM.replace(
        "<inertial><pose>0.1 0 0 0 0 0</pose><mass>0.5</mass>\n"
        "      <inertia><ixx>0.001</ixx><iyy>0.002</iyy><izz>0.002</izz></inertia></inertial>",
        "",
    )
    # The loader already refuses it; the planner refuses it too for models built in code.
    with pytest.raises(DescriptionError, match=r"'upper'.*inertial"):
        plan_model(parse_model(text))
    import dataclasses

    model = parse_model(ARM)
    massless = dataclasses.replace(
        model, links=tuple(dataclasses.replace(lk, inertial=None) if lk.name == "upper" else lk for lk in model.links)
    )
    with pytest.raises(DescriptionError, match=r"'upper'.*no mass.*inertial"):
        plan_model(massless)


def test_static_models_and_world_anchored_trees_do_not_move() -> None:
    pendulum = """<model name="pendulum"><pose>0 0 2 0 0 0</pose>
      <link name="bob"><pose>0.5 0 0 0 0 0</pose>
        <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
        <collision name="c"><geometry><sphere><radius>0.05</radius></sphere></geometry></collision></link>
      <joint name="pivot" type="revolute"><parent>world</parent><child>bob</child><pose>-0.5 0 0 0 0 0</pose>
        <axis><xyz>0 1 0</xyz></axis></joint></model>"""
    statue = """<model name="statue"><static>true</static><pose>3 0 0.5 0 0 0</pose>
      <link name="a"><collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision></link>
      <link name="b"><pose>0 0 1 0 0 0</pose><collision name="c"><geometry><sphere><radius>0.2</radius></sphere>
      </geometry></collision></link></model>"""
    pw, ents = build(sdf_world(ground() + pendulum + statue))
    try:
        for _ in range(600):
            pw.step()
        # The bob swings about the pivot at (0, 0, 2): always 0.5 m from it, and it fell below the pivot height.
        bob = ents["pendulum"].link_pose("bob").xyz
        assert math.dist(bob, (0, 0, 2)) == pytest.approx(0.5, abs=1e-3)
        assert bob[2] < 1.9
        assert ents["statue"].link_pose("b").is_close(Pose((3, 0, 1.5)), 1e-9)
        assert ents["statue"].plan.bodies[0].static_base
    finally:
        pw.close()


def test_prismatic_and_ball_joints_move_as_their_axes_allow() -> None:
    rig = """<model name="rig"><pose>0 0 1 0 0 0</pose>
      <link name="rail"><inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia>
        </inertial></link>
      <joint name="fix" type="fixed"><parent>world</parent><child>rail</child></joint>
      <link name="slider"><pose>0 0 0 0 0 0</pose>
        <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial></link>
      <joint name="slide" type="prismatic"><parent>rail</parent><child>slider</child>
        <axis><xyz>0 0 -1</xyz><limit><lower>0</lower><upper>0.3</upper></limit></axis></joint>
      <link name="bob"><pose>0.4 0 0 0 0 0</pose>
        <inertial><mass>0.5</mass><inertia><ixx>0.001</ixx><iyy>0.001</iyy><izz>0.001</izz></inertia></inertial></link>
      <joint name="swivel" type="ball"><parent>slider</parent><child>bob</child><pose>-0.4 0 0 0 0 0</pose></joint>
    </model>"""
    pw, ents = build(sdf_world(rig))
    try:
        e = ents["rig"]
        assert set(e.joints) == {"slide", "swivel"}
        assert pb.getJointInfo(e.joints["swivel"].body, e.joints["swivel"].index, physicsClientId=pw.client)[2] == (
            pb.JOINT_SPHERICAL
        )
        lowest = 0.0
        for k in range(800):
            pw.step()
            if k % 20 == 0:
                slider, bob = e.link_pose("slider").xyz, e.link_pose("bob").xyz
                # The bob hangs from the ball joint: always 0.4 m from it, and it swings through the bottom.
                assert math.dist(bob, slider) == pytest.approx(0.4, abs=2e-3)
                lowest = min(lowest, bob[2] - slider[2])
        assert lowest < -0.35
        # The slider fell down its rail to the lower stop (0.3 m along -z); the rail stays put.
        assert e.joint_states([e.joint("slide")])[0][0] == pytest.approx(0.3, abs=0.01)
        assert e.link_pose("rail").is_close(Pose((0, 0, 1)), 1e-6)
        assert e.link_pose("slider").xyz == pytest.approx((0, 0, 0.7), abs=0.01)
    finally:
        pw.close()


CUBE_OBJ = """# a 0.2 m cube centred at the origin
v -0.1 -0.1 -0.1
v 0.1 -0.1 -0.1
v 0.1 0.1 -0.1
v -0.1 0.1 -0.1
v -0.1 -0.1 0.1
v 0.1 -0.1 0.1
v 0.1 0.1 0.1
v -0.1 0.1 0.1
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
"""


def test_mesh_geometry_collides_at_its_scaled_size(tmp_path) -> None:
    (tmp_path / "cube.obj").write_text(CUBE_OBJ)
    crate = f"""<model name="crate"><pose>0 0 1 0 0 0</pose><link name="l">
      <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
      <collision name="c"><geometry><mesh><uri>{tmp_path / "cube.obj"}</uri><scale>2 2 2</scale></mesh></geometry>
      </collision>
      <visual name="v"><geometry><mesh><uri>{tmp_path / "cube.obj"}</uri><scale>2 2 2</scale></mesh></geometry></visual>
    </link></model>"""
    pw, ents = build(sdf_world(ground() + crate))
    try:
        for _ in range(1500):
            pw.step()
        # Scaled to 0.4 m, it rests with its centre 0.2 m above the ground.
        assert ents["crate"].link_pose("l").xyz[2] == pytest.approx(0.2, abs=0.01)
    finally:
        pw.close()


def test_one_link_with_two_surfaces_keeps_both_frictions_and_its_exact_mass() -> None:
    # A URDF caster lumped into base_link keeps its own <mu1> 0.01 (Gazebo applies it per collision).
    from diffctl.description.urdf.to_model import urdf_model
    from tests.sim.idle_robots import urdf_with_caster

    model = urdf_model(urdf_with_caster())
    (body,) = plan_model(model).bodies
    assert len(body.links) == 4  # base, two wheels, the caster's surface
    base, split = body.links[0], body.links[3]
    assert {base.surface.mu, split.surface.mu} == {1.0, 0.01}
    assert split.parent == -1 and split.joint is None and split.part_of == ("base_footprint",)
    assert [c.geometry.radius_m for c in split.collisions] == [0.025]
    mass = sum(lk.mass_kg for lk in (base, split))
    assert mass == pytest.approx(2.05)
    assert base.inertial_frame == split.inertial_frame
    assert [a + b for a, b in zip(base.inertia_diagonal, split.inertia_diagonal, strict=True)] == pytest.approx(
        principal(combine([from_inertial(model.link("base_footprint").inertial, Pose())]))[1]
    )
    pw, _ = build(sdf_world(ground()))
    try:
        entity = pw.add_model(model)
        cid, b = pw.client, entity.bodies[0]
        frictions = sorted(pb.getDynamicsInfo(b, i, physicsClientId=cid)[1] for i in (-1, 2))
        assert frictions == [0.01, 1.0]
    finally:
        pw.close()


def test_a_wheel_cylinder_meets_the_world_as_a_contact_disc_and_a_core_and_other_cylinders_stay() -> None:
    from sim_helpers import CAR

    from diffctl.description.model import Cylinder
    from diffctl.description.sdf_loader import load_model
    from diffctl.sim.wheel_contact import CORE_RADIUS_SHARE, DISC_LENGTH_M

    plan = plan_model(load_model(CAR, name="robot", pose=Pose.from_xyz_rpy((0, 0, 0), (0, 0, 0.7))))
    by_name = {m: lp for lp in plan.bodies[0].links for m in lp.members}
    for wheel in ("left_wheel", "right_wheel"):
        shapes = [s.geometry for s in by_name[wheel].collisions]
        assert shapes == [
            Cylinder(0.04, DISC_LENGTH_M),
            Cylinder(pytest.approx(0.04 * (1 - CORE_RADIUS_SHARE)), 0.02),
        ]
        assert all(s.surface.mu == 1.0 for s in by_name[wheel].collisions)
        assert [v.geometry for v in by_name[wheel].visuals] == [Cylinder(0.04, 0.02)]  # visuals untouched
    # The lidar's cylinder is on a fixed joint: unchanged.
    assert any(s.geometry == Cylinder(0.03, 0.04) for lp in plan.bodies[0].links for s in lp.collisions)
    # A cylinder on a revolute joint that does not turn about its own axis (a flap) is unchanged too.
    model = parse_model("""<?xml version="1.0"?><sdf version="1.8"><model name="m">
      <link name="a"><inertial><mass>1</mass></inertial></link>
      <link name="b"><inertial><mass>1</mass></inertial>
        <collision name="c"><pose>0.1 0 0 0 0 0</pose>
          <geometry><cylinder><radius>0.05</radius><length>0.1</length></cylinder></geometry></collision></link>
      <joint name="j" type="revolute"><parent>a</parent><child>b</child><axis><xyz>0 0 1</xyz></axis></joint>
    </model></sdf>""")
    flap = {m: lp for lp in plan_model(model).bodies[0].links for m in lp.members}["b"]
    assert [s.geometry for s in flap.collisions] == [Cylinder(0.05, 0.1)]


def test_links_split_off_mid_tree_keep_the_numbers_pybullet_gives_them() -> None:
    """createMultiBody numbers links depth first, whatever order they come in: a surface split off the first of
    two arms (appended to the plan) is numbered before the second arm, and the plan says so."""
    surface = "<surface><friction><ode><mu>{}</mu></ode></friction></surface>"
    shapes = "".join(
        f"<collision name='c{k}'><pose>0 {0.1 * k} 0 0 0 0</pose><geometry><box><size>0.1 0.1 0.1</size></box>"
        f"</geometry>{surface.format(mu)}</collision>"
        for k, mu in enumerate((1.0, 0.2))
    )
    inertial = "<inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>"
    arms = "".join(
        f"<link name='arm{i}'><pose>{i} 0 1 0 0 0</pose>{inertial}{shapes if i == 1 else ''}</link>"
        f"<joint name='j{i}' type='revolute'><parent>base</parent><child>arm{i}</child><axis><xyz>0 0 1</xyz></axis>"
        "</joint>"
        for i in (1, 2)
    )
    model = f"<model name='m'><pose>0 0 0 0 0 0</pose><link name='base'>{inertial}</link>{arms}</model>"
    world = sdf_world(model)
    (body,) = plan_model(world.model("m")).bodies
    assert [lp.members or lp.part_of for lp in body.links] == [("base",), ("arm1",), ("arm1",), ("arm2",)]
    pw, ents = build(world)
    try:
        entity = ents["m"]
        cid, b = pw.client, entity.bodies[0]
        for index, lp in enumerate(body.links[1:]):
            assert pb.getLinkState(b, index, physicsClientId=cid)[4] == pytest.approx(lp.frame_world.xyz)
            assert pb.getJointInfo(b, index, physicsClientId=cid)[16] == lp.parent
        assert entity.link_pose("arm2").xyz == pytest.approx((2.0, 0.0, 1.0))
        assert pb.getDynamicsInfo(b, 1, physicsClientId=cid)[1] == pytest.approx(0.2)  # the split, after arm1
    finally:
        pw.close()
