"""Finding the workspace and its packages, precedence over install trees and diffctl's packages, the
materialised share tree, and the errors."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from diffctl import workspace
from diffctl.errors import ConfigError
from diffctl.workspace import PackageNotFoundError, find_package, find_workspace, list_packages, share_dir
from tests.workspace.conftest import package_xml, snapshot, write_tree

CMAKE_PKG = """cmake_minimum_required(VERSION 3.8)
project({name})
find_package(ament_cmake REQUIRED)
install(DIRECTORY launch config DESTINATION share/${{PROJECT_NAME}})
ament_package()
"""


def cmake_package(root: Path, name: str, extra: dict[str, str] | None = None) -> Path:
    return write_tree(
        root,
        {
            "package.xml": package_xml(name),
            "CMakeLists.txt": CMAKE_PKG.format(name=name),
            "launch/bringup.launch.py": f"# {name}\n",
            "config/params.yaml": f"owner: {name}\n",
            **(extra or {}),
        },
    )


def install_tree(prefix: Path, name: str, *, symlink_to: Path | None = None) -> Path:
    """An installed package as colcon leaves it (a symlink install when `symlink_to` is given)."""
    share = prefix / "share" / name
    share.mkdir(parents=True)
    marker = prefix / "share/ament_index/resource_index/packages" / name
    marker.parent.mkdir(parents=True, exist_ok=True)
    marker.write_text("")
    if symlink_to is not None:
        (share / "package.xml").symlink_to(symlink_to)
    else:
        (share / "package.xml").write_text(package_xml(name))
    return prefix


@pytest.fixture
def ws(tmp_path: Path) -> Path:
    root = tmp_path / "ws"
    cmake_package(root / "src" / "robot_description", "robot_description")
    cmake_package(root / "src" / "group" / "diff_sim", "diff_sim")
    return root


def test_the_workspace_is_found_from_any_folder_inside_it(ws: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    deep = ws / "src" / "group" / "diff_sim" / "launch"
    monkeypatch.chdir(deep)
    assert find_workspace() == ws.resolve()
    assert find_workspace(start=ws.parent) is None
    assert find_workspace(explicit=ws / "src") == ws.resolve()  # naming src/ itself is understood
    monkeypatch.setenv("DIFFCTL_WORKSPACE", str(ws))
    monkeypatch.chdir(ws.parent)
    assert find_workspace() == ws.resolve()


def test_an_unrelated_src_above_the_working_directory_is_no_workspace(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    home = tmp_path / "home"
    # ~/src of other repositories: a ROS package whose CMake hook only exists after a build, and a non-ROS
    # package.xml; a project beside it is no workspace (this used to apply that hook and fail)
    other = cmake_package(home / "src" / "someone_elses", "someone_elses")
    (other / "CMakeLists.txt").write_text(
        "project(someone_elses)\nament_environment_hooks(${CMAKE_CURRENT_BINARY_DIR}/generated.dsv)\nament_package()\n"
    )
    (home / "src" / "js_thing").mkdir(parents=True)
    (home / "src" / "js_thing" / "package.xml").write_text("<project/>")
    project = home / "project" / "launch"
    project.mkdir(parents=True)
    monkeypatch.chdir(project)
    assert find_workspace() is None
    assert find_workspace(start=home) == home.resolve()  # typed in the folder itself, it is taken
    assert find_workspace(start=home / "src" / "someone_elses") == home.resolve()
    # once colcon has built there, any folder inside counts (ws/launch of a tutorial layout)
    (home / "install").mkdir()
    (home / "install" / "COLCON_IGNORE").write_text("")
    assert find_workspace(start=home / "project") == home.resolve()
    # a src/ holding only non-ROS package.xml files is none
    stray = tmp_path / "stray"
    (stray / "src" / "x").mkdir(parents=True)
    (stray / "src" / "x" / "package.xml").write_text("<project/>")
    assert find_workspace(start=stray) is None


def test_naming_a_folder_that_is_no_workspace_is_an_error(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    with pytest.raises(ConfigError, match=r"--workspace: .* is not a workspace \(no src/ folder"):
        find_workspace(explicit=tmp_path)
    monkeypatch.setenv("DIFFCTL_WORKSPACE", str(tmp_path / "nope"))
    with pytest.raises(ConfigError, match=r"DIFFCTL_WORKSPACE: .* is not a directory"):
        find_workspace()


def test_the_crawl_skips_ignored_hidden_and_nested_packages(ws: Path) -> None:
    cmake_package(ws / "src" / "ignored" / "skipped_a", "skipped_a")
    (ws / "src" / "ignored" / "COLCON_IGNORE").write_text("")
    cmake_package(ws / "src" / "skipped_b", "skipped_b")
    (ws / "src" / "skipped_b" / "AMENT_IGNORE").write_text("")
    cmake_package(ws / "src" / ".git" / "skipped_c", "skipped_c")
    cmake_package(ws / "src" / "robot_description" / "nested" / "skipped_d", "skipped_d")
    found = {p.name: p for p in list_packages(ws)}
    assert {n for n, p in found.items() if p.origin == "workspace"} == {"robot_description", "diff_sim"}
    # the package's name is <name>, not its folder
    cmake_package(ws / "src" / "folder_name", "real_name")
    assert find_package("real_name", ws).source == ws / "src" / "folder_name"


def test_user_packages_win_over_install_trees_which_win_over_diffctl_demos(
    ws: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    first = install_tree(tmp_path / "opt1", "robot_description")
    install_tree(first, "only_installed")
    second = install_tree(tmp_path / "opt2", "only_installed")
    install_tree(second, "diffctl_demo")
    monkeypatch.setenv("AMENT_PREFIX_PATH", os.pathsep.join([str(first), "", str(tmp_path / "gone"), str(second)]))
    assert find_package("robot_description", ws).origin == "workspace"
    assert share_dir("only_installed") == first / "share" / "only_installed"  # first prefix wins
    assert workspace.package_prefix("only_installed") == first
    assert find_package("diffctl_demo", ws).share == second / "share" / "diffctl_demo"
    assert find_package("diffctl_demo_description", ws).origin == "diffctl"


def test_a_users_package_named_like_a_replaced_ros_package_wins(tmp_path: Path, monkeypatch) -> None:
    root = tmp_path / "ws"
    cmake_package(root / "src" / "ros_gz_sim", "ros_gz_sim")
    monkeypatch.chdir(root)
    found = find_package("ros_gz_sim")
    assert (found.origin, found.source) == ("workspace", root / "src" / "ros_gz_sim")
    monkeypatch.chdir(tmp_path)
    assert (share_dir("ros_gz_sim") / "launch" / "gz_sim.launch.py").is_file()  # diffctl's own


def test_colcon_prefix_path_isolated_and_merged_layouts(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    isolated = tmp_path / "ws1" / "install"
    install_tree(isolated / "pkg_iso", "pkg_iso")
    (isolated / ".colcon_install_layout").parent.mkdir(parents=True, exist_ok=True)
    (isolated / ".colcon_install_layout").write_text("isolated\n")
    merged = install_tree(tmp_path / "ws2" / "install", "pkg_merged")
    (merged / ".colcon_install_layout").write_text("merged\n")
    monkeypatch.setenv("COLCON_PREFIX_PATH", os.pathsep.join([str(isolated), str(merged)]))
    assert find_package("pkg_iso").prefix == isolated / "pkg_iso"
    assert find_package("pkg_merged").prefix == merged
    assert find_package("pkg_iso").origin == "COLCON_PREFIX_PATH"


def test_a_stale_install_never_wins_over_the_sources(ws: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # colcon build --symlink-install, then the sources moved: every link in install/ points nowhere.
    install = ws / "install"
    (install / "COLCON_IGNORE").parent.mkdir(parents=True)
    (install / "COLCON_IGNORE").write_text("")
    for name in ("diff_sim", "removed_pkg"):
        install_tree(install / name, name, symlink_to=ws / "old_src" / name / "package.xml")
    monkeypatch.setenv("AMENT_PREFIX_PATH", f"{install / 'removed_pkg'}{os.pathsep}{install / 'diff_sim'}")
    monkeypatch.chdir(ws)
    assert find_package("diff_sim").origin == "workspace"
    with pytest.raises(PackageNotFoundError, match=r"skipped stale install AMENT_PREFIX_PATH .*no longer exists"):
        share_dir("removed_pkg")
    assert "removed_pkg" not in {p.name for p in list_packages()}


def test_the_share_tree_follows_the_sources_and_never_writes_into_the_workspace(
    ws: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(ws)
    before = snapshot(ws)
    share = share_dir("diff_sim")
    assert sorted(p.relative_to(share).as_posix() for p in share.rglob("*") if p.is_file()) == [
        "config/params.yaml",
        "launch/bringup.launch.py",
        "package.xml",
    ]
    assert (share / "launch" / "bringup.launch.py").resolve() == ws / "src/group/diff_sim/launch/bringup.launch.py"
    marker = share.parent / "ament_index/resource_index/packages/diff_sim"
    assert marker.is_file()
    # a file the user adds appears on the next resolution, a deleted one goes
    (ws / "src/group/diff_sim/launch/added.launch.py").write_text("")
    (ws / "src/group/diff_sim/config/params.yaml").unlink()
    share = share_dir("diff_sim")
    assert (share / "launch" / "added.launch.py").is_file()
    assert not (share / "config").exists()
    after = snapshot(ws)
    assert set(after) - set(before) == {"src/group/diff_sim/launch/added.launch.py"}
    assert set(before) - set(after) == {"src/group/diff_sim/config/params.yaml"}


def test_a_package_with_cpp_targets_and_a_python_package_resolve(tmp_path: Path, monkeypatch) -> None:
    root = tmp_path / "ws"
    cmake_package(
        root / "src" / "hw",
        "hw",
        {"src/driver.cpp": "int main() {}\n", "CMakeLists.txt": CMAKE_PKG.format(name="hw")
         + "add_executable(driver src/driver.cpp)\ninstall(TARGETS driver DESTINATION lib/${PROJECT_NAME})\n"},
    )
    write_tree(
        root / "src" / "py_nodes",
        {
            "package.xml": package_xml("py_nodes", "ament_python"),
            "setup.py": "from setuptools import setup\nsetup(name='py_nodes', data_files=[('share/py_nodes/launch', "
            "['launch/n.launch.py'])], entry_points={'console_scripts': ['hello = py_nodes.hi:main']})\n",
            "launch/n.launch.py": "",
            "py_nodes/__init__.py": "",
            "py_nodes/hi.py": "def main():\n    print('hi from the workspace')\n    return 0\n",
        },
    )
    monkeypatch.chdir(root)
    assert (share_dir("hw") / "launch" / "bringup.launch.py").is_file()
    py = find_package("py_nodes")
    assert py.build_type == "ament_python"
    assert (py.share / "launch" / "n.launch.py").is_file()
    script = py.prefix / "lib" / "py_nodes" / "hello"
    assert os.access(script, os.X_OK)
    import subprocess

    assert subprocess.run([str(script)], capture_output=True, text=True, timeout=60).stdout == "hi from the workspace\n"


def test_an_unknown_package_names_what_was_searched_and_close_matches(ws: Path, monkeypatch) -> None:
    monkeypatch.chdir(ws)
    with pytest.raises(PackageNotFoundError) as e:
        share_dir("robot_descripton")
    text = str(e.value)
    assert "package 'robot_descripton' not found (did you mean 'robot_description' or" in text
    assert f"workspace {ws.resolve()} (2 packages)" in text
    assert "diffctl's packages" in text
    assert e.value.exit_code == 2
    assert isinstance(e.value, KeyError)  # as ament_index_python's PackageNotFoundError
    with pytest.raises(ConfigError, match="is not a valid package name"):
        share_dir("../etc")


def test_duplicate_and_broken_manifests_are_reported(ws: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    cmake_package(ws / "src" / "copy", "diff_sim")
    write_tree(ws / "src" / "broken", {"package.xml": "<package><name>broken</name>\n"})
    monkeypatch.chdir(ws)
    with pytest.raises(ConfigError, match="package 'diff_sim' is defined twice"):
        share_dir("diff_sim")
    assert find_package("robot_description").origin == "workspace"
    with pytest.raises(PackageNotFoundError, match=r"unreadable: .*broken/package.xml:2:\d+: malformed package.xml"):
        share_dir("brokn")


def test_the_cache_of_a_deleted_workspace_goes_when_another_arrives(tmp_path: Path, monkeypatch) -> None:
    import shutil

    from diffctl.workspace.share_tree import workspace_cache

    first, second = tmp_path / "ws1", tmp_path / "ws2"
    cmake_package(first / "src" / "pkg_a", "pkg_a")
    cmake_package(second / "src" / "pkg_b", "pkg_b")
    share_a = find_package("pkg_a", first).share
    assert (share_a / "package.xml").is_file()
    cache_a = share_a.parents[2]
    assert cache_a == workspace_cache(first)
    shutil.rmtree(first)
    find_package("pkg_b", second)
    assert not cache_a.exists()
    assert (find_package("pkg_b", second).share / "package.xml").is_file()


def test_the_package_index_maps_ros_names_to_diffctl_components() -> None:
    import sys

    from diffctl.workspace import package_index

    repo = Path(__file__).resolve().parents[2]
    argv = package_index.executable_argv("controller_manager", "ros2_control_node")
    assert argv == [sys.executable, "-m", "diffctl", "control", "manager"]
    assert package_index.executable_argv("ros_gz_bridge", "parameter_bridge")[-1] == "bridge"
    assert package_index.share_dir("diffctl_demo") == repo
    assert package_index.find_launch_file("teleop") == repo / "launch" / "teleop.yaml"


def test_the_project_packages_resolve_from_an_installed_wheel_layout(tmp_path: Path, monkeypatch) -> None:
    from diffctl.workspace import package_index

    share = tmp_path / "share"
    (share / "launch").mkdir(parents=True)
    (share / "description").mkdir()
    (share / "launch" / "demo.launch.py").write_text("")
    monkeypatch.setenv("DIFFCTL_PROJECT_DIR", str(share))
    assert package_index.share_dir("diffctl_demo_description") == share / "description"
    assert package_index.find_launch_file("demo", cwd=tmp_path) == share / "launch" / "demo.launch.py"
    assert package_index.find_launch_file("diffctl_demo", "demo.launch.py") == share / "launch" / "demo.launch.py"
