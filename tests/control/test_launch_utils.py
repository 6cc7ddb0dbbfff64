"""controller_manager.launch_utils as launch files use it: one shell-run spawner built by the helper, against a
real manager on mock hardware over a real router — controllers, their parameter file, extra spawner arguments,
and the helper's own `unload_on_kill` launch argument (true: the spawner unloads them when the launch stops)."""

from __future__ import annotations

import signal
import subprocess
import time

import pytest
from test_mock_control import CONFIG, SDF

LAUNCH = """\
from controller_manager.launch_utils import generate_controllers_spawner_launch_description


def generate_launch_description():
    return generate_controllers_spawner_launch_description(
        ['joint_state_broadcaster', 'diffbot_base_controller'],
        controller_params_files=[{config!r}],
        extra_spawner_args=['--inactive'],
    )
"""
BOUND_S = 60.0  # a failure bound, never a guess of how long something takes


@pytest.mark.slow
def test_spawner_helper_loads_its_controllers_and_unloads_them_on_kill(router, procs, tmp_path, monkeypatch):
    from diffctl.client import runtime
    from diffctl.client.node import Node
    from diffctl.client.signals import SignalHandlerOptions
    from diffctl.control.cm_client import ManagerClient

    monkeypatch.setenv("ROS_HOME", str(tmp_path))
    procs.diffctl(
        "control", "manager", "--description", str(SDF), "--param-file", str(CONFIG),
        "--hardware-plugin", "mock_components/GenericSystem", "--ros-args", "-p", "use_sim_time:=false",
        stdout=(tmp_path / "manager.log").open("w"), stderr=subprocess.STDOUT,
    )  # fmt: skip
    path = tmp_path / "spawn.launch.py"
    path.write_text(LAUNCH.format(config=str(CONFIG)))
    runtime.init(args=["test_launch_utils"], signal_handler_options=SignalHandlerOptions.NO)
    try:
        cm = ManagerClient(Node("test_launch_utils"))
        cm.wait("list_controllers", BOUND_S)
        launch = procs.diffctl("launch", str(path), "unload_on_kill:=true", "--no-router")
        deadline = time.monotonic() + BOUND_S
        states: dict[str, str] = {}
        while states != {"joint_state_broadcaster": "inactive", "diffbot_base_controller": "inactive"}:
            assert time.monotonic() < deadline and launch.poll() is None, (states, launch.poll())
            states = {c.name: c.state for c in cm.list_controllers()}
        assert procs.stop(launch, signal.SIGINT, timeout_s=BOUND_S) == 0
        out = launch.stdout.read()
        assert "--unload-on-kill" in out and f"--param-file {CONFIG}" in out, out  # the spawner's command line
        assert cm.list_controllers() == [], out  # --unload-on-kill: unloaded when the launch stopped it
    finally:
        runtime.try_shutdown()
