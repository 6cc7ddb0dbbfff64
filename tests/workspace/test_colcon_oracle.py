"""Discovery and ament_python data files against colcon itself: `colcon list` must find the packages the
crawl finds, and `colcon build --symlink-install` must install the data files the index maps."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from diffctl.workspace.resolve import install_index, scan_workspace
from tests.workspace.conftest import package_xml, write_tree

COLCON = shutil.which("colcon", path=str(Path(sys.executable).parent)) or shutil.which("colcon")
needs_colcon = pytest.mark.skipif(COLCON is None, reason="colcon_not_installed: the oracle is colcon itself")


def colcon(ws: Path, *args: str) -> str:
    env = {k: v for k, v in os.environ.items() if k not in ("AMENT_PREFIX_PATH", "COLCON_PREFIX_PATH")}
    r = subprocess.run(
        [str(COLCON), "--log-base", str(ws / "log"), *args],
        cwd=ws, capture_output=True, text=True, timeout=300, env=env,
    )
    assert r.returncode == 0, r.stdout + r.stderr
    return r.stdout


def cmake_package(root: Path, name: str) -> None:
    # the project() name agrees with <name>: colcon's CMake identification reads the former
    write_tree(root, {"package.xml": package_xml(name), "CMakeLists.txt": f"project({name})\n"})


PY_TEMPLATE = """import os
from glob import glob
from setuptools import setup

package_name = '{name}'
setup(
    name=package_name,
    version='0.1.0',
    packages=[package_name],
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        (os.path.join('share', package_name, 'launch'), glob(os.path.join('launch', '*launch.[pxy][yma]*'))),
        (os.path.join('share', package_name, 'config'), glob('config/*')),
        (f'share/{{package_name}}/urdf', ['urdf/robot.urdf']),
    ],
    entry_points={{'console_scripts': ['talker = {name}.talker:main']}},
)
"""


def python_package(root: Path, name: str) -> None:
    write_tree(
        root,
        {
            "package.xml": package_xml(name, "ament_python"),
            "setup.py": PY_TEMPLATE.format(name=name),
            # ros2 pkg create's setup.cfg: console scripts go where `ros2 run` looks
            "setup.cfg": f"[develop]\nscript_dir=$base/lib/{name}\n[install]\ninstall_scripts=$base/lib/{name}\n",
            f"resource/{name}": "",
            f"{name}/__init__.py": "",
            f"{name}/talker.py": "def main():\n    return 0\n",
            "launch/bringup.launch.py": "",
            "launch/other.launch.xml": "",
            "launch/notes.txt": "",
            "config/a.yaml": "",
            "config/b.yaml": "",
            "urdf/robot.urdf": "",
        },
    )


@needs_colcon
def test_the_crawl_finds_what_colcon_list_finds(tmp_path: Path) -> None:
    ws = tmp_path / "ws"
    cmake_package(ws / "src" / "robot_a", "robot_a")
    cmake_package(ws / "src" / "group" / "deep" / "robot_b", "robot_b")
    cmake_package(ws / "src" / "robot_a" / "nested" / "robot_c", "robot_c")  # inside a package: not one
    cmake_package(ws / "src" / "skipped" / "robot_d", "robot_d")
    (ws / "src" / "skipped" / "COLCON_IGNORE").write_text("")
    cmake_package(ws / "src" / "ament_skipped" / "robot_e", "robot_e")
    (ws / "src" / "ament_skipped" / "AMENT_IGNORE").write_text("")
    cmake_package(ws / "src" / ".hidden" / "robot_f", "robot_f")
    python_package(ws / "src" / "py_robot", "py_robot")
    listed = {}
    for line in colcon(ws, "list", "--base-paths", "src").splitlines():
        name, path, _ = line.split("\t")
        listed[name] = (ws / path).resolve()
    scan = scan_workspace(ws)
    assert {n: m.path.parent.resolve() for n, m in scan.manifests.items()} == listed
    assert set(listed) == {"robot_a", "robot_b", "py_robot"}


@needs_colcon
def test_data_files_are_what_colcon_symlink_installs(tmp_path: Path) -> None:
    ws = tmp_path / "ws"
    python_package(ws / "src" / "py_robot", "py_robot")
    colcon(ws, "build", "--symlink-install", "--base-paths", "src", "--build-base", "build",
           "--install-base", "install")
    prefix = ws / "install" / "py_robot"
    installed = {}
    for dirpath, _, filenames in os.walk(prefix / "share"):
        for name in filenames:
            p = Path(dirpath) / name
            if p.is_symlink():  # colcon's own hooks are real files; the data files are links
                installed[p.relative_to(prefix).as_posix()] = p.resolve()
    index = install_index(scan_workspace(ws).manifests["py_robot"])
    assert not index.problems
    assert {d: f.source.resolve() for d, f in index.files.items()} == installed
    assert index.console_scripts == {"talker": "py_robot.talker:main"}
    assert (prefix / "lib" / "py_robot" / "talker").is_file()  # where colcon puts the console script too
