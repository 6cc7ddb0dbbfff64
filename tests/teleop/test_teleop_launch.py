"""launch/teleop.yaml takes the tutorial's line and gives `teleop joy` the settings teleop-launch.py would."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from diffctl import ros_args
from diffctl.launch import commandline, loader, resolver
from diffctl.launch.plan import StartProcess, walk
from diffctl.teleop.cli import JOY_NODE, joy_settings
from tests.probe import Probe

LAUNCH = Path(__file__).resolve().parents[2] / "launch" / "teleop.yaml"
TUTORIAL = {"joy_config": "xbox", "publish_stamped_twist": "true", "joy_vel": "/diffbot_base_controller/cmd_vel"}


def joy_command_line(arguments: dict[str, str], tmp_path: Path) -> list[str]:
    plan = resolver.resolve(loader.load(LAUNCH), arguments, str(LAUNCH))
    (spec,) = [s.spec for s in walk(plan.steps) if isinstance(s, StartProcess)]
    return commandline.argv(spec, tmp_path, write=True)


@pytest.mark.parametrize(
    ("arguments", "preset", "stamped", "topic"),
    [
        (TUTORIAL, "xbox", True, "/diffbot_base_controller/cmd_vel"),
        ({}, "ps3", False, "/cmd_vel"),  # upstream's defaults
    ],
)
def test_launch_line_reaches_teleop_joy(
    router: str, tmp_path: Path, arguments: dict[str, str], preset: str, stamped: bool, topic: str
) -> None:
    argv = joy_command_line(arguments, tmp_path)
    assert argv[1:5] == ["-m", "diffctl", "teleop", "joy"]
    _, ros = ros_args.split_argv(argv[1:])
    ra = ros_args.parse(ros, JOY_NODE)
    settings = joy_settings(ra, None, None, None, None)
    assert (settings.preset, settings.params.publish_stamped_twist) == (preset, stamped)
    assert (settings.params.enable_button, settings.params.deadzone, settings.device_id) == (
        {"xbox": "LB", "ps3": "L2"}[preset],
        0.3,
        0,
    )
    node = Probe(ra.node_name, remaps=ra.remaps)
    try:
        assert node.fqn == "/teleop_twist_joy_node"
        assert node.resolve(settings.topic) == topic
    finally:
        node.close()


def test_cli_defaults_target_our_controller_stamped() -> None:
    settings = joy_settings(ros_args.parse([], JOY_NODE), None, None, None, None)
    assert (settings.preset, settings.topic, settings.params.publish_stamped_twist) == (
        "ps3",
        "/diffbot_base_controller/cmd_vel",
        True,
    )


def test_tutorial_line_runs_and_a_missing_pad_is_reported(router: str) -> None:
    args = [f"{k}:={v}" for k, v in TUTORIAL.items()] + ["joy_dev:=99"]
    r = subprocess.run(
        [sys.executable, "-m", "diffctl", "launch", "teleop", *args],
        capture_output=True,
        text=True,
        timeout=60,
        start_new_session=True,
    )
    out = " ".join((r.stdout + r.stderr).split())
    assert "[teleop_twist_joy_node]" in out and "no game pad number 99" in out, out
