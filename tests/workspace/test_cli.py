"""`diffctl pkg …` and `diffctl launch PKG FILE` in a user's workspace, as real processes."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.workspace.conftest import package_xml, snapshot, write_tree

CMAKE = """cmake_minimum_required(VERSION 3.8)
project(my_bot)
find_package(ament_cmake REQUIRED)
install(DIRECTORY launch config urdf DESTINATION share/${PROJECT_NAME})
install(DIRECTORY worlds_missing DESTINATION share/${PROJECT_NAME})
install(PROGRAMS scripts/hello.sh DESTINATION lib/${PROJECT_NAME})
ament_package()
"""

# A child started from another folder must still find the package: the workspace travels in the environment.
LAUNCH = """launch:
- executable:
    name: resolver
    cwd: /
    cmd: "{python} -m diffctl pkg prefix --share my_bot"
- node: {{pkg: my_bot, exec: hello.sh, name: hello}}
- executable: {{name: xacro, cwd: /, cmd: "xacro $(find-pkg-share my_bot)/urdf/bot.urdf.xacro"}}
"""

XACRO = """<?xml version="1.0"?>
<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base"><visual><geometry><mesh filename="$(find my_bot)/config/params.yaml"/></geometry></visual></link>
</robot>
"""


def diffctl(*args: str, cwd: Path, env: dict[str, str] | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "diffctl", *args],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=cwd,
        env={**os.environ, **(env or {})},
    )


@pytest.fixture
def ws(tmp_path: Path) -> Path:
    root = tmp_path / "ws"
    write_tree(
        root / "src" / "my_bot",
        {
            "package.xml": package_xml("my_bot"),
            "CMakeLists.txt": CMAKE,
            "launch/bringup.launch.yaml": LAUNCH.format(python=sys.executable),
            "config/params.yaml": "a: 1\n",
            "urdf/bot.urdf.xacro": XACRO,
            "scripts/hello.sh": "#!/bin/sh\necho hello from my_bot\n",
        },
    )
    (root / "src/my_bot/scripts/hello.sh").chmod(0o755)
    write_tree(root / "src" / "py_bot", {"package.xml": package_xml("py_bot", "ament_python"), "setup.py": "setup("})
    return root


def test_pkg_list_and_prefix_show_what_was_found_and_from_where(ws: Path) -> None:
    # Wide enough for any temporary folder's path (under pytest-xdist it has a popen-gwN level more).
    r = diffctl("pkg", "list", cwd=ws / "src" / "my_bot", env={"COLUMNS": "400"})
    assert r.returncode == 0, r.stderr
    assert f"workspace: {ws}" in r.stdout
    rows = {line.split()[0]: line for line in r.stdout.splitlines() if line.strip() and line.split()[0].isidentifier()}
    assert "workspace" in rows["my_bot"] and str(ws / "src" / "my_bot") in rows["my_bot"]
    assert "diffctl" in rows["ros_gz_sim"] and "diffctl" in rows["diffctl_demo"]
    assert "executables only" in rows["controller_manager"]
    assert "warning: my_bot: CMakeLists.txt:5: directory worlds_missing does not exist" in r.stderr
    assert "warning: py_bot: setup.py:1: syntax error" in r.stderr
    r = diffctl("pkg", "--workspace", str(ws), "prefix", "--share", "my_bot", cwd=ws.parent)
    assert r.returncode == 0, r.stderr
    share = Path(r.stdout.strip())
    assert (share / "config" / "params.yaml").resolve() == ws / "src/my_bot/config/params.yaml"
    assert diffctl("pkg", "executables", "my_bot", cwd=ws).stdout.splitlines() == ["my_bot hello.sh"]
    assert diffctl("pkg", "xml", "my_bot", cwd=ws).stdout == package_xml("my_bot")


def test_unknown_packages_and_launch_files_exit_2_naming_the_search(ws: Path) -> None:
    r = diffctl("pkg", "prefix", "my_bott", cwd=ws)
    assert r.returncode == 2
    (line,) = r.stderr.strip().splitlines()
    assert "package 'my_bott' not found (did you mean 'my_bot' or 'py_bot'?)" in line
    assert f"searched: workspace {ws} (2 packages)" in line
    r = diffctl("launch", "my_bot", "bringup.launch.yml", "--print", cwd=ws)
    assert r.returncode == 2
    warning, line = r.stderr.strip().splitlines()
    assert warning.startswith("warning: package 'my_bot'") and "worlds_missing does not exist" in warning
    assert f"no launch file 'bringup.launch.yml' in package 'my_bot' (workspace {ws / 'src' / 'my_bot'})" in line
    assert "did you mean 'bringup.launch.yaml'" in line
    r = diffctl("launch", "--workspace", str(ws.parent), "my_bot", "bringup.launch.yaml", cwd=ws)
    assert r.returncode == 2 and "is not a workspace" in r.stderr


def test_launch_resolves_the_users_package_and_children_resolve_the_same(ws: Path, tmp_path: Path) -> None:
    before = snapshot(ws)
    elsewhere = tmp_path / "elsewhere"
    r = diffctl(
        "launch", "--workspace", str(ws), "my_bot", "bringup.launch.yaml", "--no-router",
        "--log-dir", str(tmp_path / "logs"), cwd=elsewhere,
    )
    assert r.returncode == 0, r.stdout + r.stderr
    share = next(line for line in r.stdout.splitlines() if line.startswith("[resolver] ")).split()[-1]
    assert (Path(share) / "launch" / "bringup.launch.yaml").resolve() == ws / "src/my_bot/launch/bringup.launch.yaml"
    assert "hello from my_bot" in r.stdout
    # an install rule that installs nothing is said once, not left to a missing file later
    assert r.stderr.count("CMakeLists.txt:5: directory worlds_missing does not exist") == 1
    # the real xacro, run as a command, resolves $(find) through diffctl's ament_index_python
    assert f'filename="{share}/config/params.yaml"' in r.stdout
    assert snapshot(ws) == before  # nothing written into the user's workspace
