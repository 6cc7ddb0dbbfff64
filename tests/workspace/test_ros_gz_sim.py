"""ros_gz_sim's gz_sim.launch.py as diffctl ships it: every argument, Gazebo's built-in world names, and
the package exports on GZ_SIM_RESOURCE_PATH — read through the launch engine as a user's include is."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.launch_requests import Run, started
from tests.workspace.conftest import package_xml, write_tree

INCLUDE = """
import os
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource

def generate_launch_description():
    gz = os.path.join(get_package_share_directory("ros_gz_sim"), "launch", "gz_sim.launch.py")
    return LaunchDescription([
        IncludeLaunchDescription(PythonLaunchDescriptionSource(gz), launch_arguments={ARGS}.items()),
    ])
"""


def run_for(tmp_path: Path, args: dict[str, str]) -> Run:
    path = tmp_path / "include.launch.py"
    path.write_text(INCLUDE.replace("{ARGS}", repr(args)))
    return started(path)


def resource_path(env: dict[str, str | None]) -> list[str]:
    return (env.get("GZ_SIM_RESOURCE_PATH") or "").split(os.pathsep)


def test_gz_args_reach_the_simulator_and_builtin_world_names_resolve(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("GZ_SIM_RESOURCE_PATH", "/users/own/models")
    run = run_for(tmp_path, {"gz_args": "-r -s -v 4 empty.sdf", "on_exit_shutdown": "True"})
    (sim,) = run.started
    assert sim.argv[-6:] == ["run", "-r", "-s", "-v", "4", "empty.sdf"]
    assert run.required_exit  # on_exit_shutdown
    paths = resource_path(sim.env)
    assert paths[0] == "/users/own/models"  # the user's entries come before Gazebo's own worlds
    assert Path(paths[-1], "empty.sdf").is_file()
    from diffctl.sim.cli import find_world

    monkeypatch.setenv("GZ_SIM_RESOURCE_PATH", os.pathsep.join(paths))
    world = find_world("empty.sdf")
    assert Path(world).parent == Path(paths[-1])
    from diffctl.description.sdf_loader import load_world

    assert load_world(world).name == "empty"


def test_gui_only_starts_nothing_and_any_on_exit_shutdown_text_shuts_down(tmp_path: Path) -> None:
    assert not run_for(tmp_path, {"gz_args": "-g -v4 "}).started
    assert not run_for(tmp_path, {"gz_args": "-rg"}).started
    # ros_gz_sim (jazzy) tests the string: its default 'false', or 'maybe', still shuts the launch down
    for value in ("false", "maybe"):
        run = run_for(tmp_path, {"gz_args": "-r world.sdf", "on_exit_shutdown": value})
        assert len(run.started) == 1 and run.required_exit
    run = run_for(tmp_path, {"gz_args": "-v -v1 -r world.sdf", "on_exit_shutdown": ""})
    assert len(run.started) == 1 and not run.required_exit


def test_deprecated_and_composition_arguments_are_accepted(tmp_path: Path) -> None:
    run = run_for(
        tmp_path,
        {
            "ign_args": "-r -s empty.sdf",
            "ign_version": "6",
            "debugger": "false",
            "container_name": "c",
            "create_own_container": "false",
            "use_composition": "true",
        },
    )
    (sim,) = run.started
    assert sim.argv[-3:] == ["-r", "-s", "empty.sdf"]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        ({"gz_version": "harmonic"}, "gz_version:='harmonic' of gz_sim.launch.py is not a version number"),
        ({"gz_args": "-r 'unclosed"}, "cannot be split"),
    ],
)
def test_bad_arguments_are_one_error(tmp_path: Path, args: dict[str, str], message: str, caplog) -> None:
    run = run_for(tmp_path, args)
    assert run.code == 1 and not run.started
    caught = [r.getMessage() for r in caplog.records if "Caught exception in launch" in r.getMessage()]
    assert len(caught) == 1 and message in caught[0]


def test_package_model_path_exports_join_the_resource_path(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    ws = tmp_path / "ws"
    xml = package_xml("my_models").replace(
        "<export>", '<export><gazebo_ros gazebo_model_path="${prefix}/.." plugin_path="${prefix}/plugins"/>'
    )
    write_tree(
        ws / "src" / "my_models",
        {
            "package.xml": xml,
            "CMakeLists.txt": "project(my_models)\ninstall(DIRECTORY models DESTINATION share/${PROJECT_NAME})\n",
            "models/box/model.sdf": "<sdf version='1.8'><model name='box'/></sdf>",
        },
    )
    monkeypatch.chdir(ws)
    (sim,) = run_for(tmp_path, {"gz_args": "-r empty.sdf"}).started
    exported = Path(resource_path(sim.env)[0])
    # model://my_models/models/box/model.sdf resolves under the exported folder, live from the sources
    assert (exported / "my_models" / "models" / "box" / "model.sdf").resolve() == (
        ws / "src/my_models/models/box/model.sdf"
    )
    assert sim.env["GZ_SIM_SYSTEM_PLUGIN_PATH"].endswith("my_models/plugins")


def server_run(tmp_path: Path, args: dict[str, str]) -> Run:
    path = tmp_path / "server.launch.py"
    path.write_text(INCLUDE.replace("gz_sim.launch.py", "gz_server.launch.py").replace("{ARGS}", repr(args)))
    return started(path)


def test_gz_server_launch_runs_a_world_file_or_text(tmp_path: Path, caplog) -> None:
    (sim,) = server_run(tmp_path, {"world_sdf_file": "/worlds/w.sdf"}).started
    assert sim.argv[-3:] == ["-r", "-s", "/worlds/w.sdf"]
    (sim,) = server_run(tmp_path, {"start_paused": "True"}).started
    assert sim.argv[-2:] == ["-s", "empty.sdf"]
    text = (Path(resource_path(sim.env)[-1]) / "empty.sdf").read_text()
    (sim,) = server_run(tmp_path, {"world_sdf_string": text}).started
    written = Path(sim.argv[-1])
    assert written.read_text() == text and (tmp_path / "cache") in written.parents  # diffctl's cache only
    run = server_run(tmp_path, {"world_sdf_file": "/w.sdf", "world_sdf_string": text})
    assert run.code == 1 and not run.started
    assert any("not both" in r.getMessage() for r in caplog.records)
