"""RIHS01 type hashes equal rosidl's: every hash the real Jazzy packages install (share/<pkg>/*/*.json, from
rosidl_generator_type_description) for the packages diffctl serves, messages, services and their parts."""

from __future__ import annotations

import json

import pytest

from diffctl.interfaces import get_interface, registry, type_hash, types
from tests.oracle import jazzy_venv

PACKAGES = ["action_msgs", "builtin_interfaces", "diagnostic_msgs", "geometry_msgs", "lifecycle_msgs", "nav_msgs",
            "rcl_interfaces", "rosgraph_msgs", "sensor_msgs", "service_msgs", "shape_msgs", "std_msgs", "std_srvs",
            "trajectory_msgs", "type_description_interfaces", "unique_identifier_msgs", "visualization_msgs"]


def real_hashes(pkg: str) -> dict[str, str]:
    out = {}
    for path in sorted(jazzy_venv.share(pkg).glob("*/*.json")):
        for entry in json.loads(path.read_text())["type_hashes"]:
            out[entry["type_name"]] = entry["hash_string"]
    return out


@pytest.mark.parametrize("pkg", PACKAGES)
def test_hashes_equal_rosidl(pkg: str) -> None:
    real = real_hashes(pkg)
    assert real, f"the oracle has no type descriptions of {pkg}"
    for name, expected in real.items():
        registry.package(name.split("/")[0])
        assert types.type_hash(name) == expected, name


def test_classes_hash_as_their_types() -> None:
    real = real_hashes("std_srvs") | real_hashes("geometry_msgs")
    assert type_hash(get_interface("std_srvs/srv/Trigger")) == real["std_srvs/srv/Trigger"]
    assert type_hash(get_interface("std_srvs/srv/Trigger").Request) == real["std_srvs/srv/Trigger_Request"]
    twist = get_interface("geometry_msgs/msg/Twist")
    assert type_hash(twist()) == type_hash(twist) == real["geometry_msgs/msg/Twist"]
