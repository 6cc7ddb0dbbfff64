"""A workspace whose `test_msgs` package is the real one's interface files (from the oracle venv), declared
to rosidl_generate_interfaces the way test_msgs' CMakeLists does: globbed lists, a variable, DEPENDENCIES."""

from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.oracle import jazzy_venv

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3">
  <name>test_msgs</name>
  <version>2.0.3</version>
  <description>rosidl's test interfaces, as a workspace package</description>
  <maintainer email="a@b.c">a</maintainer>
  <license>Apache-2.0</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <buildtool_depend>rosidl_default_generators</buildtool_depend>
  <depend>builtin_interfaces</depend>
  <depend>unique_identifier_msgs</depend>
  <member_of_group>rosidl_interface_packages</member_of_group>
  <export><build_type>ament_cmake</build_type></export>
</package>
"""

CMAKELISTS = """cmake_minimum_required(VERSION 3.8)
project(test_msgs)
find_package(ament_cmake REQUIRED)
find_package(rosidl_default_generators REQUIRED)
find_package(builtin_interfaces REQUIRED)
file(GLOB msg_files RELATIVE "${CMAKE_CURRENT_SOURCE_DIR}" "msg/*.msg")
set(srv_files
  "srv/Arrays.srv"
  "srv/BasicTypes.srv"
  "srv/Empty.srv"
)
list(APPEND srv_files ${action_files})
rosidl_generate_interfaces(${PROJECT_NAME}
  ${msg_files}
  ${srv_files}
  "action/Fibonacci.action"
  "action/NestedMessage.action"
  DEPENDENCIES builtin_interfaces unique_identifier_msgs
  ADD_LINTER_TESTS
)
ament_package()
"""


@pytest.fixture(autouse=True)
def _bus_definitions_restored() -> Iterator[None]:
    """Tests here load interface packages in this process, which enters their types in the bus's definitions:
    taken out again afterwards, so later tests of the same run (tests/graph's oracle checks over every
    defined type) see diffctl's own definitions only."""
    from diffctl.interfaces import registry, typedefs

    defs = typedefs.definitions()
    before = dict(defs)
    yield
    defs.clear()
    defs.update(before)
    registry.reset()


@pytest.fixture(scope="session")
def test_msgs_workspace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    ws = tmp_path_factory.mktemp("ws")
    pkg = ws / "src" / "test_msgs"
    share = jazzy_venv.share("test_msgs")
    for kind in ("msg", "srv", "action"):
        (pkg / kind).mkdir(parents=True)
        for f in (share / kind).glob(f"*.{kind}"):
            shutil.copy(f, pkg / kind / f.name)
    (pkg / "package.xml").write_text(PACKAGE_XML)
    (pkg / "CMakeLists.txt").write_text(CMAKELISTS)
    return ws
