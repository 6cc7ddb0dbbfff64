"""Per-link `<gravity>` and `<self_collide>` in real PyBullet, against the SDF rules (link.sdf) and free-fall
kinematics: a link without gravity floats, a body half without it falls at the matching fraction of g, links of
one model collide only when one of them self-collides, and never across a joint."""

from __future__ import annotations

import pytest
from sim_helpers import build, ground, sdf_world

G = 9.8  # sdf_world's default <gravity>


def box_link(name: str, z: float, mass: float, extra: str = "", size: str = "0.2 0.2 0.2", x: float = 0.0) -> str:
    i = mass * 0.2**2 / 6
    return f"""<link name="{name}"><pose>{x} 0 {z} 0 0 0</pose>{extra}
      <inertial><mass>{mass}</mass><inertia><ixx>{i}</ixx><iyy>{i}</iyy><izz>{i}</izz></inertia></inertial>
      <collision name="c"><geometry><box><size>{size}</size></box></geometry></collision></link>"""


def test_a_link_without_gravity_floats_and_a_part_without_it_lightens_the_fall() -> None:
    floater = f'<model name="floater">{box_link("b", 5.0, 1.0, "<gravity>false</gravity>")}</model>'
    stone = f'<model name="stone"><pose>2 0 0 0 0 0</pose>{box_link("b", 5.0, 1.0)}</model>'
    # One body of 1 kg with gravity and 3 kg without (a fixed joint merges them): a = g · 1 / 4.
    half = f"""<model name="half"><pose>4 0 0 0 0 0</pose>{box_link("heavy", 5.0, 1.0)}
      {box_link("light", 5.3, 3.0, "<gravity>false</gravity>")}
      <joint name="weld" type="fixed"><parent>heavy</parent><child>light</child></joint></model>"""
    pw, ents = build(sdf_world(floater + stone + half))
    try:
        steps = 500
        for _ in range(steps):
            pw.step()
        t = steps * pw.step_s
        assert ents["floater"].link_pose("b").xyz[2] == pytest.approx(5.0, abs=1e-6)
        assert ents["stone"].link_pose("b").xyz[2] == pytest.approx(5.0 - 0.5 * G * t * t, abs=0.01)
        assert ents["half"].link_pose("heavy").xyz[2] == pytest.approx(5.0 - 0.5 * (G / 4) * t * t, abs=0.01)
    finally:
        pw.close()


def sliders(self_collide_left: bool = False, model_self_collide: bool = False) -> str:
    """A base pinned to the world with two sibling sliders on x; the left one is driven into the right one."""
    flag = "<self_collide>true</self_collide>" if self_collide_left else ""
    model_flag = "<self_collide>true</self_collide>" if model_self_collide else ""
    joints = "".join(
        f"""<joint name="{n}" type="prismatic"><parent>base</parent><child>{n}_slider</child>
          <axis><xyz>1 0 0</xyz><limit><lower>-2</lower><upper>2</upper></limit></axis></joint>"""
        for n in ("left", "right")
    )
    return f"""<model name="rig">{model_flag}
      {box_link("base", 1.0, 1.0, size="0.05 0.05 0.05", x=0.0)}
      <joint name="pin" type="fixed"><parent>world</parent><child>base</child></joint>
      {box_link("left_slider", 1.0, 1.0, flag, x=-0.5)}{box_link("right_slider", 1.0, 1.0, x=0.5)}{joints}</model>"""


@pytest.mark.parametrize(
    ("left", "model", "collide"),
    [(False, False, False), (True, False, True), (False, True, True)],
    ids=["neither", "one-link-self-collides", "model-self-collides"],
)
def test_links_of_one_model_collide_only_when_one_self_collides(left: bool, model: bool, collide: bool) -> None:
    pw, ents = build(sdf_world(sliders(left, model)))
    try:
        rig = ents["rig"]
        lead, other = rig.joint("left"), rig.joint("right")
        rig.release_joint(other)
        for _ in range(1500):
            rig.set_joint_velocity(lead, 1.0)
            pw.step()
        (q_lead, _, _), (q_other, _, _) = rig.joint_states([lead, other])
        # Both sliders pass the base (joined to it, so never colliding with it) at x = 0.
        assert q_lead > 1.0
        if collide:
            assert q_other > 0.3  # pushed along
        else:
            assert q_other == pytest.approx(0.0, abs=1e-6)  # passed through
    finally:
        pw.close()


@pytest.mark.parametrize("self_collide", [False, True])
def test_separate_trees_of_one_model_follow_the_same_rule(self_collide: bool) -> None:
    flag = "<self_collide>true</self_collide>" if self_collide else ""
    stack = f"""<model name="stack">{box_link("bottom", 0.1, 1.0)}{box_link("top", 0.5, 1.0, flag)}</model>"""
    pw, ents = build(sdf_world(ground() + stack))
    try:
        for _ in range(1500):
            pw.step()
        top_z = ents["stack"].link_pose("top").xyz[2]
        # On the bottom box (0.3 m) when they collide, through it to the ground (0.1 m) when they do not.
        assert top_z == pytest.approx(0.3 if self_collide else 0.1, abs=0.01)
    finally:
        pw.close()


def test_never_across_a_joint_even_where_a_link_is_split_in_pybullet() -> None:
    """A link whose collisions have two surfaces is two PyBullet links; the second is no parent of the links
    joined to the SDF link, and still must not collide with them."""
    floating = "<gravity>false</gravity>"  # (a base pinned to the world is static: one surface, no split)
    base = box_link("base", 1.0, 5.0, floating, size="0.05 0.05 0.05").replace(
        "</link>",
        '<collision name="ledge"><pose>0.3 0 0 0 0 0</pose><geometry><box><size>0.05 0.3 0.3</size></box>'
        "</geometry><surface><friction><ode><mu>0.2</mu></ode></friction></surface></collision></link>",
    )
    rig = f"""<model name="rig"><self_collide>true</self_collide>{base}
      {box_link("slider", 1.0, 1.0, floating, x=-0.5)}<joint name="slide" type="prismatic"><parent>base</parent>
      <child>slider</child><axis><xyz>1 0 0</xyz><limit><lower>-2</lower><upper>2</upper></limit></axis></joint>
    </model>"""
    pw, ents = build(sdf_world(rig))
    try:
        entity = ents["rig"]
        assert len(entity.plan.bodies[0].links) == 3  # base, slider, the ledge's surface
        slide = entity.joint("slide")
        for _ in range(1500):
            entity.set_joint_velocity(slide, 1.0)
            pw.step()
        assert entity.joint_states([slide])[0][0] > 1.0  # through the ledge
    finally:
        pw.close()
