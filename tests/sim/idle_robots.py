"""Robot shapes that must stand still when nobody drives them: SDF/URDF texts written the way community robots
write them (TurtleBot-style sphere caster, sliding box caster, 4-wheel skid steer, a URDF robot with a caster
and Gazebo friction extensions), plus the tutorial car from the repository."""

from __future__ import annotations

import math


def _inertial(mass: float, ixx: float, iyy: float, izz: float, pose: str = "0 0 0 0 0 0") -> str:
    return (
        f"<inertial><pose>{pose}</pose><mass>{mass}</mass><inertia><ixx>{ixx}</ixx><ixy>0</ixy><ixz>0</ixz>"
        f"<iyy>{iyy}</iyy><iyz>0</iyz><izz>{izz}</izz></inertia></inertial>"
    )


def _wheel(name: str, x: float, y: float, z: float, r: float, w: float, surface: str) -> str:
    m = 0.1
    ixx = m * (3 * r * r + w * w) / 12
    return f"""<link name="{name}"><pose relative_to="base_link">{x} {y} {z} -1.5707963 0 0</pose>
      {_inertial(m, ixx, ixx, m * r * r / 2)}
      <collision name="{name}_c"><geometry><cylinder><radius>{r}</radius><length>{w}</length></cylinder></geometry>
        {surface}</collision>
      <visual name="{name}_v"><geometry><cylinder><radius>{r}</radius><length>{w}</length></cylinder></geometry>
      </visual>
    </link>
    <joint name="{name}_joint" type="revolute"><parent>base_link</parent><child>{name}</child>
      <axis><xyz>0 0 1</xyz>
        <limit><lower>-1e16</lower><upper>1e16</upper><effort>2</effort><velocity>20</velocity></limit>
        <dynamics><damping>0.0</damping><friction>0.0</friction></dynamics></axis></joint>"""


# TurtleBot3's Gazebo wheels: high friction along a direction, stiff contact (kp/kd), small min depth.
TB_WHEEL_SURFACE = """<surface><friction><ode><mu>100000.0</mu><mu2>100000.0</mu2><fdir1>0 0 1</fdir1>
  <slip1>0.0</slip1><slip2>0.0</slip2></ode></friction>
  <contact><ode><soft_cfm>0</soft_cfm><soft_erp>0.2</soft_erp><kp>1e+5</kp><kd>1</kd><max_vel>0.01</max_vel>
  <min_depth>0.001</min_depth></ode></contact></surface>"""


def turtlebot_like(caster: str = "sphere", caster_mu: float = 0.1) -> str:
    """Two driven wheels and one rear caster fixed to the base: a small sphere, or a sliding box."""
    r, sep = 0.033, 0.16
    if caster == "sphere":
        cgeom = "<sphere><radius>0.005</radius></sphere>"
        cz = -0.028
    else:
        cgeom = "<box><size>0.030 0.009 0.020</size></box>"
        cz = -0.023
    return f"""<?xml version="1.0"?>
<sdf version="1.8"><model name="tb">
  <link name="base_footprint"/>
  <link name="base_link"><pose>0 0 0.033 0 0 0</pose>
    {_inertial(0.8, 0.0072, 0.0072, 0.0060, "-0.032 0 0.04 0 0 0")}
    <collision name="body"><pose>-0.032 0 0.07 0 0 0</pose>
      <geometry><box><size>0.14 0.14 0.12</size></box></geometry></collision>
  </link>
  <joint name="base_joint" type="fixed"><parent>base_footprint</parent><child>base_link</child></joint>
  {_wheel("wheel_left", 0, sep / 2, 0, r, 0.018, TB_WHEEL_SURFACE)}
  {_wheel("wheel_right", 0, -sep / 2, 0, r, 0.018, TB_WHEEL_SURFACE)}
  <link name="caster_back"><pose relative_to="base_link">-0.081 0 {cz + 0.0} 0 0 0</pose>
    {_inertial(0.005, 1e-6, 1e-6, 1e-6)}
    <collision name="caster_c"><geometry>{cgeom}</geometry>
      <surface><friction><ode><mu>{caster_mu}</mu><mu2>{caster_mu}</mu2></ode></friction>
      <contact><ode><kp>1e+6</kp><kd>100</kd><min_depth>0.001</min_depth><max_vel>1.0</max_vel></ode></contact></surface>
    </collision>
  </link>
  <joint name="caster_joint" type="fixed"><parent>base_link</parent><child>caster_back</child></joint>
</model></sdf>"""


def skid_steer() -> str:
    """Four driven wheels, no caster."""
    r = 0.05
    surf = "<surface><friction><ode><mu>1.0</mu><mu2>1.0</mu2></ode></friction></surface>"
    wheels = "".join(
        _wheel(f"wheel_{n}", x, y, 0, r, 0.04, surf)
        for n, x, y in (("fl", 0.12, 0.14), ("fr", 0.12, -0.14), ("rl", -0.12, 0.14), ("rr", -0.12, -0.14))
    )
    return f"""<?xml version="1.0"?>
<sdf version="1.8"><model name="skid">
  <link name="base_link"><pose>0 0 0.05 0 0 0</pose>
    {_inertial(3.0, 0.03, 0.05, 0.07, "0 0 0.03 0 0 0")}
    <collision name="body"><pose>0 0 0.04 0 0 0</pose>
      <geometry><box><size>0.36 0.22 0.08</size></box></geometry></collision>
  </link>
  {wheels}
</model></sdf>"""


def urdf_with_caster() -> str:
    """A URDF robot: two wheels, a rear sphere caster on a fixed joint, Gazebo friction set by <gazebo> tags."""
    r = 0.05

    def wheel(side: str, y: float) -> str:
        ixx = 0.2 * (3 * r * r + 0.03**2) / 12
        return f"""<link name="{side}_wheel"><inertial><mass value="0.2"/>
        <inertia ixx="{ixx}" ixy="0" ixz="0" iyy="{ixx}" iyz="0" izz="{0.2 * r * r / 2}"/></inertial>
        <collision><origin rpy="{math.pi / 2} 0 0"/>
          <geometry><cylinder radius="{r}" length="0.03"/></geometry></collision>
        <visual><origin rpy="{math.pi / 2} 0 0"/>
          <geometry><cylinder radius="{r}" length="0.03"/></geometry></visual></link>
      <joint name="{side}_wheel_joint" type="continuous"><parent link="base_link"/><child link="{side}_wheel"/>
        <origin xyz="0.05 {y} 0"/><axis xyz="0 1 0"/><dynamics damping="0.01" friction="0.0"/></joint>
      <gazebo reference="{side}_wheel"><mu1>1.0</mu1><mu2>1.0</mu2><kp>1000000.0</kp><kd>100.0</kd>
        <fdir1>1 0 0</fdir1></gazebo>"""

    return f"""<?xml version="1.0"?>
<robot name="urdfbot">
  <link name="base_footprint"/>
  <joint name="footprint_joint" type="fixed"><parent link="base_footprint"/><child link="base_link"/>
    <origin xyz="0 0 {r}"/></joint>
  <link name="base_link"><inertial><origin xyz="-0.05 0 0.03"/><mass value="2.0"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.025"/></inertial>
    <collision><origin xyz="-0.05 0 0.04"/><geometry><box size="0.3 0.2 0.06"/></geometry></collision></link>
  {wheel("left", 0.13)}
  {wheel("right", -0.13)}
  <link name="caster"><inertial><mass value="0.05"/><inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/>
    </inertial><collision><geometry><sphere radius="0.025"/></geometry></collision></link>
  <joint name="caster_joint" type="fixed"><parent link="base_link"/><child link="caster"/>
    <origin xyz="-0.17 0 -0.025"/></joint>
  <gazebo reference="caster"><mu1>0.01</mu1><mu2>0.01</mu2></gazebo>
</robot>"""
