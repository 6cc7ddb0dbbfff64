"""rosidl_runtime_py as upstream's (Jazzy) computes it with the real generated classes: conversions to dicts,
YAML and CSV with truncation and abbreviation, set_message_fields, and finding interfaces by name. The
expected outputs (data/rosidl_runtime_py_jazzy.json) are upstream's own, made by make_runtime_golden.py."""

from __future__ import annotations

import json
from pathlib import Path

from tests.interfaces.programs import assert_same, run_ours
from tests.interfaces.runtime_program import PROGRAM

GOLDEN = Path(__file__).parent / "data" / "rosidl_runtime_py_jazzy.json"


def test_runtime_py_as_upstream(test_msgs_workspace) -> None:
    ours = run_ours(PROGRAM, {"DIFFCTL_WORKSPACE": str(test_msgs_workspace)})
    assert_same(ours, json.loads(GOLDEN.read_text()))


def test_interface_listing(test_msgs_workspace) -> None:
    ours = run_ours(r'''
from rosidl_runtime_py import get_interfaces, get_message_interfaces, get_action_interfaces, get_interface_path
from rosidl_runtime_py import get_service_interfaces, get_interface_packages
obs('std_srvs', lambda: get_interfaces(['std_srvs']))
obs('msgs', lambda: get_message_interfaces(['example_interfaces'])['example_interfaces'][:3])
obs('actions', lambda: get_action_interfaces(['example_interfaces', 'test_msgs']))
obs('services', lambda: get_service_interfaces(['geometry_msgs']))
obs('unknown', lambda: get_interfaces(['nope_msgs']))
obs('packages', lambda: {'test_msgs', 'geometry_msgs', 'example_interfaces'} <= set(get_interface_packages()))
obs('path', lambda: get_interface_path('test_msgs/msg/Arrays').endswith('src/test_msgs/msg/Arrays.msg'))
obs('path of a store type', lambda: get_interface_path('geometry_msgs/msg/Twist'))
obs('path, suffix given', lambda: get_interface_path('test_msgs/action/Fibonacci.action').endswith('.action'))
obs('path, another suffix', lambda: get_interface_path('test_msgs/msg/Arrays.idl'))
obs('packages without interfaces', lambda: get_interfaces(['rosidl_parser', 'rclpy', 'std_srvs']))
obs('messages of those', lambda: get_message_interfaces(['tf2_ros']))
''', {"DIFFCTL_WORKSPACE": str(test_msgs_workspace)})
    assert ours["std_srvs"] == ["ok", "{'std_srvs': ['srv/Empty', 'srv/SetBool', 'srv/Trigger']}"]
    assert ours["msgs"] == ["ok", "['msg/Bool', 'msg/Byte', 'msg/ByteMultiArray']"]
    assert ours["actions"] == ["ok", "{'example_interfaces': ['action/Fibonacci'], "
                                     "'test_msgs': ['action/Fibonacci', 'action/NestedMessage']}"]
    assert ours["services"] == ["ok", "{}"]
    assert ours["unknown"] == ["raise", "LookupError", "Unknown package 'nope_msgs'"]
    assert ours["packages"] == ["ok", True] and ours["path"] == ["ok", True]
    assert ours["path of a store type"][:2] == ["raise", "LookupError"]
    # A named suffix is that file or none (the source package has no generated .idl beside its .msg).
    assert ours["path, suffix given"] == ["ok", True]
    assert ours["path, another suffix"] == [
        "raise", "LookupError", "Could not find the interface 'test_msgs/msg/Arrays.idl'"]
    # Packages that exist but define no interfaces are left out, not "unknown" (ROS's are in its index).
    assert ours["packages without interfaces"] == [
        "ok", "{'std_srvs': ['srv/Empty', 'srv/SetBool', 'srv/Trigger']}"]
    assert ours["messages of those"] == ["ok", "{}"]
