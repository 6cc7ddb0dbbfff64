"""Worlds for simulator tests: the real car on the real empty world, plus hand-written SDF scenes."""

from __future__ import annotations

from pathlib import Path

from diffctl.description.model import Model, World
from diffctl.description.pose import Pose
from diffctl.description.sdf_loader import load_model, load_world, parse_world
from diffctl.sim.entity import Entity
from diffctl.sim.world import PhysicsWorld

REPO = Path(__file__).resolve().parents[2]
CAR = REPO / "description" / "my_diff_car.sdf"
CAR_CONTROL = REPO / "description" / "my_diff_car_control.sdf"
EMPTY_WORLD = REPO / "config" / "worlds" / "empty.world"
WHEEL_RADIUS_M = 0.04
WHEEL_SEPARATION_M = 0.3
LEFT, RIGHT = "base_link_to_left_wheel", "base_link_to_right_wheel"


def car_world(pose: Pose | None = None, path: Path = CAR) -> tuple[PhysicsWorld, Entity]:
    world = load_world(EMPTY_WORLD)
    pw = PhysicsWorld(world.physics)
    for m in world.models:
        pw.add_model(m)
    car = pw.add_model(load_model(path, name="robot", pose=pose))
    return pw, car


def sdf_world_text(body: str, name: str = "test") -> str:
    return f"""<?xml version="1.0"?>
<sdf version="1.8"><world name="{name}">
  <physics name="1ms" type="ignored">
    <max_step_size>0.001</max_step_size><real_time_factor>1</real_time_factor>
  </physics>
  {body}
</world></sdf>"""


def sdf_world(body: str, name: str = "test") -> World:
    return parse_world(sdf_world_text(body, name))


def ground() -> str:
    return """<model name="ground"><static>true</static><link name="l">
      <collision name="c"><geometry><plane><normal>0 0 1</normal><size>50 50</size></plane></geometry></collision>
      <visual name="v"><geometry><plane><normal>0 0 1</normal><size>50 50</size></plane></geometry></visual>
    </link></model>"""


def box(name: str, x: float, y: float, z: float, sx: float, sy: float, sz: float, yaw: float = 0.0) -> str:
    return f"""<model name="{name}"><static>true</static><pose>{x} {y} {z} 0 0 {yaw}</pose><link name="l">
      <collision name="c"><geometry><box><size>{sx} {sy} {sz}</size></box></geometry></collision>
      <visual name="v"><geometry><box><size>{sx} {sy} {sz}</size></box></geometry></visual>
    </link></model>"""


def build(world: World) -> tuple[PhysicsWorld, dict[str, Entity]]:
    pw = PhysicsWorld(world.physics)
    return pw, {m.name: pw.add_model(m) for m in world.models}


def model_named(world: World, name: str) -> Model:
    return world.model(name)
