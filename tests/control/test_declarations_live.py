"""The controller manager and the tutorial's two controllers declare what the real ones declare (names, types,
read-only flags, ranges, descriptions: upstream_declarations.py), over their parameter services; and
`--log-level` reaches the manager, its controllers and the spawner (real processes, a real router)."""

from __future__ import annotations

import subprocess
from typing import Any

import pytest
import upstream_declarations as up
from test_mock_control import CONFIG, SDF

TYPES = {1: "bool", 2: "integer", 3: "double", 4: "string", 5: "byte_array", 6: "bool_array", 7: "integer_array",
         8: "double_array", 9: "string_array"}


def described(cm: Any, node: Any, remote: str) -> dict[str, Any]:
    """Every parameter of `remote` with its descriptor, through its list_parameters / describe_parameters."""
    from diffctl.client.parameter_client import AsyncParameterClient

    client = AsyncParameterClient(node, remote)
    assert client.wait_for_services(timeout_sec=20.0)
    future = client.list_parameters()
    cm._executor.spin_until_future_complete(future, timeout_sec=20.0)
    names = list(future.result().result.names)
    future = client.describe_parameters(names)
    cm._executor.spin_until_future_complete(future, timeout_sec=20.0)
    return dict(zip(names, future.result().descriptors, strict=True))


def check(actual: dict[str, Any], expected: dict[str, tuple]) -> list[str]:
    """What differs from the expectations (name → (type, read_only, range, description))."""
    problems = sorted(f"{n}: not declared" for n in expected.keys() - actual.keys())
    problems += sorted(f"{n}: declared, not upstream" for n in actual.keys() - expected.keys())
    for name in expected.keys() & actual.keys():
        kind, read_only, rng, text = expected[name]
        d = actual[name]
        got_range = None
        if d.floating_point_range:
            got_range = (d.floating_point_range[0].from_value, d.floating_point_range[0].to_value)
        elif d.integer_range:
            got_range = (d.integer_range[0].from_value, d.integer_range[0].to_value)
        got = (TYPES.get(d.type, d.type), bool(d.read_only), got_range)
        if got != (kind, read_only, rng):
            problems.append(f"{name}: {got} != {(kind, read_only, rng)}")
        if text is not None and d.description != text:
            problems.append(f"{name}: description {d.description!r}")
    return problems


@pytest.mark.slow
def test_parameters_match_the_real_nodes_and_log_levels_reach_every_node(router, procs, tmp_path, monkeypatch):
    from diffctl.client import runtime
    from diffctl.client.node import Node
    from diffctl.client.signals import SignalHandlerOptions
    from diffctl.control.cm_client import ManagerClient

    monkeypatch.setenv("ROS_HOME", str(tmp_path))
    log = tmp_path / "manager.log"
    manager = procs.diffctl(
        "control", "manager", "--description", str(SDF), "--param-file", str(CONFIG),
        "--hardware-plugin", "mock_components/GenericSystem",
        "--ros-args", "-p", "use_sim_time:=false", "--log-level", "warn",
        stdout=log.open("w"), stderr=subprocess.STDOUT,
    )  # fmt: skip
    runtime.init(args=["test_declarations"], signal_handler_options=SignalHandlerOptions.NO)
    try:
        node = Node("test_declarations")
        cm = ManagerClient(node)
        cm.wait("list_controllers", 60.0)
        spawner = procs.diffctl(
            "spawn", "controller", "diffbot_base_controller", "joint_state_broadcaster", "--param-file", str(CONFIG),
            "--ros-args", "--log-level", "warn",
        )  # fmt: skip
        out, _ = spawner.communicate(timeout=60)
        assert spawner.returncode == 0, out
        # The spawner's INFO lines ("Loaded …", "Configured and activated …") are below its level.
        assert "[INFO]" not in out and "[spawner_" not in out, out
        assert {c.name: c.state for c in cm.list_controllers()} == {
            "diffbot_base_controller": "active", "joint_state_broadcaster": "active"}

        # The manager: its generate_parameter_library table, what its file sets (declared plainly, as
        # automatically_declare_parameters_from_overrides does), and what loading each controller declares.
        plain = {"update_rate": ("integer", False, None, ""), "use_sim_time": ("bool", False, None, ""),
                 "joint_state_broadcaster.type": ("string", False, None, "")}
        spawned = {f"{c}.{k}": (t, False, None, None) for c in ("diffbot_base_controller", "joint_state_broadcaster")
                   for k, t in {**up.PER_CONTROLLER, "params_file": "string_array"}.items()}
        spawned["diffbot_base_controller.type"] = ("string", False, None, None)
        expected = {**up.MANAGER, **up.RCLCPP_NODE, **spawned, **plain}
        assert check(described(cm, node, "/controller_manager"), expected) == []
        assert check(described(cm, node, "/diffbot_base_controller"),
                     {**up.DIFF_DRIVE, **up.CONTROLLER_BASE, **up.RCLCPP_NODE}) == []
        assert check(described(cm, node, "/joint_state_broadcaster"),
                     {**up.JOINT_STATE_BROADCASTER, **up.CONTROLLER_BASE, **up.RCLCPP_NODE}) == []
        cm.close()
        node.destroy_node()
    finally:
        runtime.try_shutdown()
    assert procs.stop(manager) == 0
    text = log.read_text()
    # The manager's and its controllers' INFO lines are below the level the command line set.
    assert "[INFO]" not in text, text[-2000:]
