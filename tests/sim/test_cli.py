"""`sim run` argument handling (Gazebo's flags, gz_args strings) and what the sim says about unknown systems."""

from __future__ import annotations

import pytest
from sim_helpers import EMPTY_WORLD, sdf_world

from diffctl.errors import ConfigError
from diffctl.sim.cli import find_world, parse_gz_args
from diffctl.sim.runner import Simulation, system_name


def test_gz_args_as_one_string_or_separate_words() -> None:
    g = parse_gz_args([" -r -s -v4 ", str(EMPTY_WORLD)])
    assert (g.run, g.server_only, g.verbosity, g.world) == (True, True, 4, str(EMPTY_WORLD))
    g = parse_gz_args(["-v", "2", "--iterations", "100", "--seed", "7", "w.sdf"])
    assert (g.run, g.verbosity, g.iterations, g.seed, g.world) == (False, 2, 100, 7, "w.sdf")
    assert parse_gz_args(["-g -v4"]).gui_only


@pytest.mark.parametrize(
    "args, needle",
    [
        (["-x"], "unknown option '-x'"),
        (["a.sdf", "b.sdf"], "more than one world"),
        (["-v", "x"], "not an integer"),
        (["-v7"], "verbosity 7"),
        (["--iterations"], "needs a value"),
    ],
)
def test_bad_arguments_are_one_clear_error(args: list[str], needle: str) -> None:
    with pytest.raises(ConfigError, match=needle):
        parse_gz_args(args)


def test_world_by_path_or_by_name(monkeypatch: pytest.MonkeyPatch, tmp_path) -> None:
    assert find_world(str(EMPTY_WORLD)) == EMPTY_WORLD
    assert find_world("empty.world").resolve() == EMPTY_WORLD.resolve()
    (tmp_path / "mine.sdf").write_text("<sdf/>")
    monkeypatch.setenv("GZ_SIM_RESOURCE_PATH", str(tmp_path))
    assert find_world("mine") == tmp_path / "mine.sdf"
    with pytest.raises(ConfigError, match=r"'nope\.world' not found"):
        find_world("nope.world")


def test_system_names_and_the_ignored_list(capsys: pytest.CaptureFixture[str]) -> None:
    assert system_name("libgz-sim-diff-drive-system.so") == "diff-drive"
    assert system_name("gz_ros2_control-system") == "gz_ros2_control"
    assert system_name("ignition-gazebo-joint-state-publisher-system") == "joint-state-publisher"
    world = sdf_world(
        '<plugin filename="gz-sim-physics-system" name="gz::sim::systems::Physics"/>'
        '<plugin filename="gz-sim-wind-effects-system" name="gz::sim::systems::WindEffects"/>'
        '<model name="m"><pose>0 0 1 0 0 0</pose><link name="l"><inertial><mass>1</mass></inertial></link>'
        '<plugin filename="libMyController.so" name="my::Controller"/></model>'
    )
    sim = Simulation(world)
    try:
        err = capsys.readouterr().err
        lines = [ln for ln in err.splitlines() if "ignored" in ln]
        assert len(lines) == 1, err
        assert "gz-sim-wind-effects-system" in lines[0] and "libMyController.so" in lines[0]
        assert "physics" not in lines[0]
    finally:
        sim.close()
