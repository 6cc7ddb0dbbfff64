"""The CMake install-rule index against CMake itself: the same CMakeLists.txt installed by `cmake --install`
must give exactly the files (and contents) the index maps."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from diffctl.errors import ConfigError
from diffctl.workspace.install_rules import cmake_install_index
from tests.workspace.conftest import write_tree

CMAKE = shutil.which("cmake")
needs_cmake = pytest.mark.skipif(CMAKE is None, reason="cmake_not_installed: the oracle is CMake itself")

SOURCES = {
    "launch/sim.launch.py": "launch",
    "launch/sub/inner.launch.py": "inner",
    "launch/.hidden.yaml": "hidden",
    "config/params.yaml": "params",
    "config/extra/more.yaml": "more",
    "config/notes.txt": "notes",
    "urdf/robot.urdf.xacro": "xacro",
    "urdf/parts/wheel.xacro": "wheel",
    "urdf/parts/wheel.stl": "stl",
    "meshes/base.stl": "base",
    "meshes/tmp/scratch.stl": "scratch",
    "scripts/run.sh": "#!/bin/sh\necho run\n",
    "worlds/empty.world": "world",
    "rviz/view.rviz": "rviz",
    "cmake/extra/CMakeLists.txt": "install(FILES ../../rviz/view.rviz DESTINATION share/${PROJECT_NAME}/from_sub)\n",
}


def oracle(pkg: Path, tmp: Path) -> dict[str, str]:
    """Installed file → its content, by running CMake's configure and install steps."""
    build, prefix = tmp / "build", tmp / "prefix"
    run = {"check": True, "capture_output": True, "text": True, "timeout": 120}
    subprocess.run([CMAKE, "-S", str(pkg), "-B", str(build), f"-DCMAKE_INSTALL_PREFIX={prefix}"], **run)
    subprocess.run([CMAKE, "--install", str(build)], **run)
    out = {}
    for dirpath, _, filenames in os.walk(prefix):
        for name in filenames:
            p = Path(dirpath) / name
            out[p.relative_to(prefix).as_posix()] = p.read_text()
    return out


def indexed(pkg: Path, name: str = "demo") -> dict[str, str]:
    index = cmake_install_index(pkg, name)
    assert not index.problems, index.problems
    return {dest: f.source.read_text() for dest, f in index.files.items()}


CASES = {
    "directory_with_and_without_slash": """
install(DIRECTORY launch urdf DESTINATION share/${PROJECT_NAME})
install(DIRECTORY meshes/ DESTINATION share/${PROJECT_NAME}/models)
""",
    "several_destinations_and_variables": """
set(SHARE_DIR share/${PROJECT_NAME})
set(DATA_DIRS config worlds)
install(DIRECTORY ${DATA_DIRS} DESTINATION ${SHARE_DIR})
install(DIRECTORY rviz/ DESTINATION "${CMAKE_INSTALL_PREFIX}/share/${PROJECT_NAME}/rviz/")
install(FILES config/params.yaml DESTINATION share/${PROJECT_NAME}/copies RENAME renamed.yaml)
install(PROGRAMS scripts/run.sh DESTINATION lib/${PROJECT_NAME})
""",
    "files_matching_exclude_and_regex": """
install(DIRECTORY urdf DESTINATION share/${PROJECT_NAME} FILES_MATCHING PATTERN "*.xacro")
install(DIRECTORY meshes/ DESTINATION share/${PROJECT_NAME}/meshes PATTERN "tmp" EXCLUDE)
install(DIRECTORY config/ DESTINATION share/${PROJECT_NAME}/config
  FILES_MATCHING REGEX "/[a-z]+\\\\.yaml$" PATTERN "extra" EXCLUDE)
install(DIRECTORY launch/ DESTINATION share/${PROJECT_NAME}/launch PATTERN ".*" EXCLUDE)
""",
    "syntax_comments_quotes_multiline_foreach_glob_subdirectory": """
#[[ a bracket comment with install(DIRECTORY bogus DESTINATION nowhere) inside ]]
install(   # a comment inside the call
  DIRECTORY
    "launch"    # quoted
    [=[worlds]=]
  DESTINATION
    share/${PROJECT_NAME}
)
foreach(dir IN ITEMS config rviz)
  install(DIRECTORY ${dir}/ DESTINATION share/${PROJECT_NAME}/loop_${dir})
endforeach()
file(GLOB MESHES meshes/*.stl)
install(FILES ${MESHES} DESTINATION share/${PROJECT_NAME}/globbed)
add_subdirectory(cmake/extra)
install(DIRECTORY missing_dir DESTINATION share/${PROJECT_NAME} OPTIONAL)
install(FILES ${CMAKE_CURRENT_SOURCE_DIR}/worlds/empty.world TYPE DATA)
""",
}


@needs_cmake
@pytest.mark.parametrize("case", sorted(CASES))
def test_the_index_installs_what_cmake_installs(case: str, tmp_path: Path) -> None:
    pkg = write_tree(tmp_path / "pkg", dict(SOURCES))
    body = "cmake_minimum_required(VERSION 3.10)\nproject(demo NONE)\n" + CASES[case]
    (pkg / "CMakeLists.txt").write_text(body)
    expected = oracle(pkg, tmp_path)
    assert expected, "CMake installed nothing: the case is wrong"
    assert indexed(pkg) == expected


def test_ament_package_installs_the_manifest_and_targets_install_nothing(tmp_path: Path) -> None:
    pkg = write_tree(
        tmp_path / "pkg",
        {
            "package.xml": "<package/>",
            "launch/a.launch.py": "",
            "src/node.cpp": "",
            "CMakeLists.txt": """cmake_minimum_required(VERSION 3.8)
project(my_robot)
find_package(ament_cmake REQUIRED)
add_executable(node src/node.cpp)
install(TARGETS node DESTINATION lib/${PROJECT_NAME})
install(DIRECTORY launch DESTINATION share/${PROJECT_NAME}/)
if(BUILD_TESTING)
  find_package(ament_lint_auto REQUIRED)
endif()
ament_package()
""",
        },
    )
    index = cmake_install_index(pkg, "my_robot")
    assert sorted(index.files) == ["share/my_robot/launch/a.launch.py", "share/my_robot/package.xml"]
    assert index.problems == []


def test_missing_sources_are_reported_with_their_line(tmp_path: Path) -> None:
    pkg = write_tree(
        tmp_path / "pkg",
        {
            "CMakeLists.txt": "project(p)\n\ninstall(DIRECTORY nope DESTINATION share/p)\n"
            "install(FILES gone.yaml DESTINATION share/p)\ninstall(DIRECTORY . DESTINATION /opt/abs)\n",
        },
    )
    problems = cmake_install_index(pkg, "p").problems
    assert problems[0] == "CMakeLists.txt:3: directory nope does not exist"
    assert problems[1] == "CMakeLists.txt:4: gone.yaml does not exist"
    assert "outside the install prefix" in problems[2]


@pytest.mark.parametrize(
    ("text", "line", "message"),
    [
        ("project(p)\ninstall(DIRECTORY launch\n  DESTINATION share/p\n", 2, "never closed"),
        ('project(p)\n\ninstall(FILES "a.yaml DESTINATION share/p)\n', 3, "unterminated quoted"),
        ("project(p)\nforeach(x a b)\ninstall(FILES ${x} DESTINATION share)\n", 2, "never closed by endforeach"),
        ("project(p)\n= oops\n", 2, "where a command was expected"),
    ],
)
def test_malformed_cmake_is_one_located_error(tmp_path: Path, text: str, line: int, message: str) -> None:
    pkg = write_tree(tmp_path / "pkg", {"CMakeLists.txt": text})
    with pytest.raises(ConfigError) as e:
        cmake_install_index(pkg, "p")
    assert e.value.line == line
    assert message in str(e.value)
    assert str(e.value).startswith(str(pkg / "CMakeLists.txt"))


def test_ament_cmake_auto_and_catkin_destinations(tmp_path: Path) -> None:
    pkg = write_tree(
        tmp_path / "pkg",
        {
            "package.xml": "<package/>",
            "launch/a.launch.py": "",
            "config/c.yaml": "",
            "rviz/v.rviz": "",
            "CMakeLists.txt": "project(auto_bot)\nfind_package(ament_cmake_auto REQUIRED)\n"
            "install(DIRECTORY rviz DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})\n"
            "ament_auto_package(INSTALL_TO_SHARE launch config USE_SCOPED_HEADER_INSTALL_DIR)\n",
        },
    )
    assert sorted(cmake_install_index(pkg, "auto_bot").files) == [
        "share/auto_bot/config/c.yaml",
        "share/auto_bot/launch/a.launch.py",
        "share/auto_bot/package.xml",
        "share/auto_bot/rviz/v.rviz",
    ]
