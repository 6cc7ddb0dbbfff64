"""Models past PyBullet's fixed capacities: 16 shapes per link, 127 links per body, binary STL only.

The TurtleBot3 house (a static model of 108 boxes and meshes) killed the simulator with SIGSEGV: PyBullet's
createCollisionShapeArray keeps 16 shapes and writes a mesh past them out of bounds; it silently dropped the
boxes past 16 too. Every shape must reach the physics, a static model of any size must load, and a moving tree
PyBullet cannot hold is one clear error naming the model.
"""

from __future__ import annotations

import struct
from pathlib import Path

import pybullet as pb
import pytest

from diffctl.description.model import Physics
from diffctl.description.sdf_loader import parse_model
from diffctl.errors import DescriptionError
from diffctl.sim.world import PhysicsWorld

TETRA = ((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((0, 0, 0), (1, 0, 0), (0, 0, 1)), ((0, 0, 0), (0, 1, 0), (0, 0, 1)), (
    (1, 0, 0),
    (0, 1, 0),
    (0, 0, 1),
)


def ascii_stl(path: Path) -> None:
    facets = "".join(
        "facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {x} {y} {z}\n" for x, y, z in t) + "endloop\nendfacet\n"
        for t in TETRA
    )
    path.write_text(f"solid tetra\n{facets}endsolid tetra\n")


def shape_count(world: PhysicsWorld, bodies: tuple[int, ...]) -> int:
    cid = world.client
    return sum(
        len(pb.getCollisionShapeData(b, i, physicsClientId=cid))
        for b in bodies
        for i in range(-1, pb.getNumJoints(b, physicsClientId=cid))
    )


def model_sdf(body: str, static: bool) -> str:
    return f'<sdf version="1.8"><model name="m"><static>{str(static).lower()}</static>{body}</model></sdf>'


@pytest.mark.parametrize("static", [True, False])
def test_a_link_with_many_shapes_and_meshes_keeps_every_one(tmp_path: Path, static: bool) -> None:
    ascii_stl(tmp_path / "tetra.stl")  # ASCII STL: PyBullet reads only binary STL (it crashed on this too)
    boxes = "".join(
        f"<collision name='b{i}'><pose>{i} 0 0 0 0 0</pose><geometry><box><size>0.5 0.5 0.5</size></box></geometry>"
        f"<surface><friction><ode><mu>{0.5 if i % 3 else 1}</mu></ode></friction></surface></collision>"
        for i in range(40)
    )
    meshes = "".join(
        f"<collision name='t{i}'><pose>0 {i + 1} 0 0 0 0</pose><geometry><mesh><uri>tetra.stl</uri></mesh></geometry>"
        "</collision><visual name='v{i}'><geometry><mesh><uri>tetra.stl</uri></mesh></geometry></visual>"
        for i in range(3)
    )
    inertial = "" if static else "<inertial><mass>2</mass></inertial>"
    model = parse_model(model_sdf(f"<link name='house'>{inertial}{boxes}{meshes}</link>", static), base_dir=tmp_path)
    world = PhysicsWorld(Physics())
    try:
        entity = world.add_model(model)
        assert shape_count(world, entity.bodies) == 43
        world.step()
        # the link's mass is shared out exactly between the PyBullet links that carry its shapes
        mass = sum(
            pb.getDynamicsInfo(b, i, physicsClientId=world.client)[0]
            for b in entity.bodies
            for i in range(-1, pb.getNumJoints(b, physicsClientId=world.client))
        )
        assert mass == pytest.approx(0.0 if static else 2.0)
    finally:
        world.close()


def test_a_static_model_of_many_links_loads_and_a_moving_tree_past_pybullets_capacity_is_refused() -> None:
    links = "".join(
        f"<link name='l{i}'><inertial><mass>1</mass></inertial><pose>{i} 0 0 0 0 0</pose>"
        + "".join(f"<collision name='c{k}'><geometry><sphere><radius>0.1</radius></sphere></geometry></collision>"
                  for k in range(17))
        + "</link>"
        for i in range(130)
    )
    world = PhysicsWorld(Physics())
    try:
        entity = world.add_model(parse_model(model_sdf(links, True)))
        assert len(entity.bodies) > 1 and shape_count(world, entity.bodies) == 130 * 17
        joints = "".join(
            f"<joint name='j{i}' type='revolute'><parent>l{i - 1}</parent><child>l{i}</child><axis><xyz>0 0 1</xyz>"
            "</axis></joint>"
            for i in range(1, 130)
        )
        world.remove("m")
        with pytest.raises(DescriptionError, match=r"model 'm': the tree rooted at link 'l0' needs \d+ PyBullet links"):
            world.add_model(parse_model(model_sdf(links + joints, False)))
    finally:
        world.close()


def test_meshes_pybullet_cannot_read_are_converted_or_left_out(tmp_path: Path) -> None:
    (tmp_path / "empty.stl").write_bytes(b"\0" * 80 + struct.pack("<I", 0))  # no triangle: crashed PyBullet
    (tmp_path / "noface.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    ascii_stl(tmp_path / "tetra.stl")
    body = "<link name='a'><inertial><mass>1</mass></inertial>" + "".join(
        f"<collision name='{n}'><geometry><mesh><uri>{n}</uri></mesh></geometry></collision>"
        for n in ("empty.stl", "noface.obj", "tetra.stl")
    ) + "</link>"
    model = parse_model(model_sdf(body, False), base_dir=tmp_path)
    world = PhysicsWorld(Physics())
    try:
        entity = world.add_model(model)
        assert shape_count(world, entity.bodies) == 1
        assert [n for n in entity.plan.notes if "holds no triangle" in n] == [
            "collision 'empty.stl' of link 'a' has no volume (mesh 'empty.stl' holds no triangle): left out",
            "collision 'noface.obj' of link 'a' has no volume (mesh 'noface.obj' holds no triangle): left out",
        ]
    finally:
        world.close()
