"""ROS 2 Jazzy interface definitions that rosbags' Jazzy store lacks, as their .msg/.srv text.

controller_manager_msgs and control_msgs are read from interface_texts/ (their Jazzy releases' own files, see
its README); a few rcl_interfaces, type_description_interfaces and std_srvs services are written out below.
Field order and types are Jazzy's, because the RIHS01 type hash (and so the rmw_zenoh key) is computed from them.
"""

from __future__ import annotations

import re
from pathlib import Path

TEXT_DIR = Path(__file__).with_name("interface_texts")


def _read_texts() -> tuple[dict[str, str], dict[str, tuple[str, str]]]:
    """The .msg/.srv files under interface_texts/<pkg>/<msg|srv>/, as their Jazzy releases publish them."""
    msgs: dict[str, str] = {}
    srvs: dict[str, tuple[str, str]] = {}
    for f in sorted(TEXT_DIR.glob("*/*/*")):
        name = f"{f.parent.parent.name}/{f.parent.name}/{f.stem}"
        if f.suffix == ".msg":
            msgs[name] = f.read_text()
        elif f.suffix == ".srv":
            # rosidl splits a service at a line of three dashes
            req, resp = re.split(r"^---[ \t]*$", f.read_text(), maxsplit=1, flags=re.MULTILINE)
            srvs[name] = (req, resp)
    return msgs, srvs


MSGS, _FILE_SRVS = _read_texts()

SRVS: dict[str, tuple[str, str]] = {
    **_FILE_SRVS,
    # Parameter services of every node (rclcpp); the spawner sets `<ctrl>.type` / `.params_file` through them.
    "rcl_interfaces/srv/SetParameters": ("rcl_interfaces/Parameter[] parameters",
                                         "rcl_interfaces/SetParametersResult[] results"),
    "rcl_interfaces/srv/GetParameters": ("string[] names", "rcl_interfaces/ParameterValue[] values"),
    "rcl_interfaces/srv/ListParameters": ("string[] prefixes\nuint64 depth\nuint64 DEPTH_RECURSIVE=0",
                                          "rcl_interfaces/ListParametersResult result"),
    "rcl_interfaces/srv/SetParametersAtomically": ("rcl_interfaces/Parameter[] parameters",
                                                   "rcl_interfaces/SetParametersResult result"),
    "rcl_interfaces/srv/DescribeParameters": ("string[] names", "rcl_interfaces/ParameterDescriptor[] descriptors"),
    "rcl_interfaces/srv/GetParameterTypes": ("string[] names", "uint8[] types"),
    # Every node's ~/get_type_description (REP-2016); the request's default (include_type_sources=true) is not
    # part of the type hash.
    "type_description_interfaces/srv/GetTypeDescription": (
        "string type_name\nstring type_hash\nbool include_type_sources",
        "bool successful\nstring failure_reason\ntype_description_interfaces/TypeDescription type_description\n"
        "type_description_interfaces/TypeSource[] type_sources\n"
        "type_description_interfaces/KeyValue[] extra_information",
    ),
    "std_srvs/srv/Empty": ("", ""),
    "std_srvs/srv/Trigger": ("", "bool success\nstring message"),
    "std_srvs/srv/SetBool": ("bool data", "bool success\nstring message"),
}
