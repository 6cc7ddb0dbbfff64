"""A URDF robot_description reaches every reader the SDF one does: TF, the visualizer, the joint state filter and
the controller manager's `<ros2_control>` and gz_ros2_control parameters."""

from __future__ import annotations

from pathlib import Path

from diffctl.control.controllers.joint_state_broadcaster import description_joint_names
from diffctl.description.pose import Pose
from diffctl.description.ros2_control import gz_ros2_control_parameters, ros2_control_blocks
from diffctl.robot_state_publisher.kinematics import KinematicTree
from diffctl.robot_state_publisher.node import load_description
from diffctl.viz.robot_model import parse_description as viz_model

URDF = (Path(__file__).resolve().parent / "data" / "urdf" / "diff_car.urdf").read_text()


def test_tf_tree_has_every_urdf_frame_as_ros_robot_state_publisher_does() -> None:
    tree = KinematicTree.from_model(load_description(URDF))
    assert tree.root == "base_footprint"
    fixed = {(s.parent, s.child): s for s in tree.fixed()}
    assert set(fixed) == {("base_footprint", "base_link"), ("base_link", "caster"), ("base_link", "lidar_link")}
    assert fixed[("base_link", "caster")].origin.is_close(Pose.from_xyz_rpy((-0.15, 0, -0.03), (0, 0, 0.5)), 1e-12)
    moving = tree.moving()
    assert set(moving) == {"left_wheel_joint", "right_wheel_joint"}
    # a continuous wheel turns about its URDF axis
    wheel = moving["left_wheel_joint"]
    assert wheel.transform(1.0).is_close(
        Pose.from_xyz_rpy((0, 0.15, -0.01), (-1.5708, 0, 0)).compose(Pose.from_xyz_rpy((0, 0, 0), (0, 0, 1.0))), 1e-9
    )


def test_visualizer_reads_a_urdf() -> None:
    robot = viz_model(URDF)
    assert robot.name == "diff_car"
    assert {"base_link", "caster", "left_wheel", "lidar_link"} <= set(robot.links)
    assert {"base_footprint", "base_link", "lidar_link"} <= set(robot.anchors)


def test_joint_state_filter_and_controller_manager_read_a_urdf() -> None:
    assert description_joint_names(URDF) == [
        "base_joint",
        "caster_joint",
        "left_wheel_joint",
        "lidar_joint",
        "right_wheel_joint",
    ]
    (block,) = ros2_control_blocks(URDF)
    assert [j.name for j in block.joints] == ["left_wheel_joint", "right_wheel_joint"]
    assert gz_ros2_control_parameters(URDF) == ["/tmp/controllers.yaml"]
