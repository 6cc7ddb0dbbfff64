"""Joint transforms of the TF tree against poses worked out by hand."""

from __future__ import annotations

import math

import numpy as np

from diffctl.description.sdf_loader import parse_model
from diffctl.robot_state_publisher.kinematics import KinematicTree

ARM = """<sdf version="1.8"><model name="arm"><static>true</static>
  <link name="base"/>
  <link name="upper"><pose>0 0 1 0 0 1.5707963267948966</pose></link>
  <joint name="shoulder" type="revolute"><pose>0.5 0 0 0 0 0</pose>
    <parent>base</parent><child>upper</child><axis><xyz>0 0 1</xyz></axis></joint>
  <link name="slider"><pose relative_to="upper">1 0 0 0 0 0</pose></link>
  <joint name="rail" type="prismatic"><parent>upper</parent><child>slider</child>
    <axis><xyz expressed_in="upper">1 0 0</xyz></axis></joint>
  <link name="tool"><pose relative_to="slider">0 0 0.1 0 0 0</pose></link>
  <joint name="mount" type="fixed"><parent>slider</parent><child>tool</child></joint>
</model></sdf>"""


def test_revolute_turns_about_the_joint_origin_and_prismatic_slides_along_its_axis() -> None:
    tree = KinematicTree.from_model(parse_model(ARM))
    assert tree.root == "base"
    moving = tree.moving()
    shoulder, rail = moving["shoulder"], moving["rail"]
    assert [s.joint for s in tree.fixed()] == ["mount"]
    # at q = 0 the child sits where the file puts it
    assert np.allclose(shoulder.transform(0.0).xyz, (0, 0, 1))
    # upper's frame is yawed 90°, the joint origin is 0.5 along upper's x (= base +y): (0, 0.5, 1) in base.
    # Turning +90° about z through that point moves upper's origin from (0,0,1) to (0.5, 0.5, 1), yaw 180°.
    turned = shoulder.transform(math.pi / 2)
    assert np.allclose(turned.xyz, (0.5, 0.5, 1), atol=1e-12)
    assert np.isclose(abs(turned.rpy[2]), math.pi, atol=1e-12)
    # the pivot itself does not move
    assert np.allclose(turned.transform_point((0.5, 0, 0)), (0, 0.5, 1), atol=1e-12)
    slid = rail.transform(0.25)
    assert np.allclose(slid.xyz, (1.25, 0, 0), atol=1e-12) and slid.quat == (0, 0, 0, 1)
