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
    "args, expected",
    [
        # gz sim 8's Ruby OptionParser: `-v` takes a following word unless it starts with '-' (bare: 3), the
        # text goes through atoi(), the last -v wins; short flags cluster; the world is the last free word
        (["-v -v1 -r w.sdf"], {"verbosity": 1, "run": True, "world": "w.sdf"}),
        (["-v", "-r", "w.sdf"], {"verbosity": 3, "run": True}),
        (["-v", "x", "w.sdf"], {"verbosity": 0, "world": "w.sdf"}),
        (["-v7"], {"verbosity": 4}),
        (["-rsv2", "w.sdf"], {"run": True, "server_only": True, "verbosity": 2}),
        (["--verbose=4", "--iter=0x10", "--seed", "0_7", "a.sdf", "b.sdf"], {"verbosity": 4, "iterations": 16,
                                                                              "seed": 7, "world": "b.sdf"}),
        (["-z", "1000", "--physics-engine", "gz-physics-bullet-featherstone-plugin", "--render-engine", "ogre2",
          "--record-topic", "/a", "--log-overwrite", "w.sdf"], {"world": "w.sdf"}),
    ],
)
def test_gz_sim_options_read_as_gz_sim_reads_them(args: list[str], expected: dict) -> None:
    g = parse_gz_args(args)
    assert {k: getattr(g, k) for k in expected} == expected


@pytest.mark.parametrize(
    "args, needle",
    [
        (["-x"], "invalid option: -x"),
        (["--render"], "ambiguous option: --render"),
        (["--iterations"], "needs a value"),
        (["--seed", "x"], "invalid argument: --seed x"),
        (["--record=yes"], "needless argument"),
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
