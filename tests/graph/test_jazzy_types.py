"""Every message and service type the project knows, checked against ROS 2 Jazzy's own type descriptions.

The oracle is rosidl's output shipped in the Jazzy wheels (see jazzy_oracle.py): for each type, the RIHS01 hash
the project computes (which is the rmw_zenoh key and token) and the field layout it would describe on
`~/get_type_description` must equal what rosidl generated for Jazzy.
"""

from __future__ import annotations

import pytest

from diffctl.interfaces import extra_texts as interfaces
from diffctl.interfaces import type_description, typedefs, types
from tests.graph import jazzy_oracle


@pytest.fixture(scope="module")
def oracle() -> dict:
    return jazzy_oracle.descriptions(jazzy_oracle.fetch())


def _without_defaults(ind: dict) -> dict:
    return {"type_name": ind["type_name"],
            "fields": [{"name": f["name"], "type": f["type"]} for f in ind["fields"]]}


def _layout(desc: dict) -> dict:
    return {"type_description": _without_defaults(desc["type_description"]),
            "referenced_type_descriptions": [_without_defaults(r) for r in desc["referenced_type_descriptions"]]}


def _top_level_types() -> list[str]:
    # Messages and services; a service's _Request/_Response/_Event parts are checked through the service.
    return sorted(n for n in typedefs.own_names() if not n.endswith(("_Request", "_Response", "_Event")))


def test_every_type_of_a_jazzy_package_matches_rosidl(oracle: dict) -> None:
    oracle_pkgs = {t.split("/")[0] for t in oracle}
    checked, wrong = 0, []
    for t in _top_level_types():
        if t.split("/")[0] not in oracle_pkgs:
            continue
        assert t in oracle, f"{t} is not a Jazzy type (its package has no such .msg/.srv)"
        want = oracle[t]
        if types.type_hash(t) != want["type_hashes"][0]["hash_string"]:
            wrong.append(f"{t}: hash {types.type_hash(t)} != Jazzy {want['type_hashes'][0]['hash_string']}")
        elif _layout(type_description.describe(t)) != _layout(want["type_description_msg"]):
            wrong.append(f"{t}: field layout differs from Jazzy")
        checked += 1
    assert not wrong, "\n".join(wrong)
    assert checked > 100, f"only {checked} types were compared"


def test_the_hash_is_computed_from_the_description_rosidl_writes(oracle: dict) -> None:
    # REP-2016's hash of our own description equals rosidl's for every type, so the service's answer and the key
    # in the graph agree with each other and with Jazzy.
    for t in ("geometry_msgs/msg/TwistStamped", "sensor_msgs/msg/JointState", "rcl_interfaces/srv/SetParameters",
              "type_description_interfaces/srv/GetTypeDescription", "rcl_interfaces/msg/Log"):
        assert type_description.hash_of(type_description.describe(t)) == oracle[t]["type_hashes"][0]["hash_string"]


def test_project_defined_types_of_jazzy_packages_are_all_checked(oracle: dict) -> None:
    ours = [*interfaces.MSGS, *interfaces.SRVS]
    covered = {t.split("/")[0] for t in oracle}
    for t in ours:
        if t.split("/")[0] in covered:
            assert t in oracle, f"{t} (defined in interfaces.py) does not exist in Jazzy"

