"""rclpy's shape as programs see it, against the real Jazzy wheel: which modules exist, which ones typical
imports load (so `rclpy.executors`, `rclpy.logging`, … are attributes after `from rclpy.node import Node`),
and parameter services run by the executor as rclpy's are."""

from __future__ import annotations

import os
import pkgutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.client.differential import assert_same, run_both
from tests.oracle import jazzy_venv

OVERLAY = Path(__file__).resolve().parents[2] / "diffctl" / "overlay"
# The C extension and its loader: rclpy's binding to rcl, which diffctl's client library has no need of.
KNOWN_ABSENT = {"rclpy._rclpy_pybind11", "rclpy._rclpy_pybind11.service_introspection", "rclpy._dummy",
                "rclpy.impl.implementation_singleton"}


def _public_modules(root: Path) -> set[str]:
    return {m.name for m in pkgutil.walk_packages([str(root / "rclpy")], "rclpy.")} | {"rclpy"}


def test_every_public_module_of_the_wheel_exists() -> None:
    ours = _public_modules(OVERLAY)
    real = _public_modules(jazzy_venv.site_packages())
    assert real - KNOWN_ABSENT - ours == set()
    assert ours - real == set()


@pytest.mark.parametrize("program", ["module_set.py", "module_set_create_node.py"])
def test_typical_imports_load_what_rclpy_loads(router: str, program: str) -> None:
    oracle, ours = run_both(program, router)
    for obs in oracle.observations:
        if isinstance(obs[1], list) and obs[1] and isinstance(obs[1][0], str):
            obs[1] = [m for m in obs[1] if m not in KNOWN_ABSENT]
    assert_same(oracle, ours)


def test_parameter_services_are_run_by_the_executor(router: str) -> None:
    """launch_testing_ros's set_param test: a request sent before the subclass declares is answered once the
    node spins, successfully; the set callback runs on the spinning thread."""
    assert_same(*run_both("param_service_executor.py", router))


def test_import_rclpy_stays_light() -> None:
    """`import rclpy` loads no node machinery (rclpy's own __init__ does not): the rest comes with rclpy.node."""
    code = "import sys, rclpy; print(sorted(m for m in sys.modules if m.startswith('diffctl.client.node')))"
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60,
                       env={**os.environ, "PYTHONPATH": str(OVERLAY)})
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "[]"


def test_qos_overrides_agree(router: str) -> None:
    """The qos_overrides demos' API: QosCallbackResult, the qos_overrides.* parameters, a refused override."""
    assert_same(*run_both("qos_overrides.py", router))


def test_service_introspection_agrees(router: str) -> None:
    """The introspection demo's API: <service>/_service_event from a service and a client, CONTENTS,
    METADATA and OFF."""
    assert_same(*run_both("service_introspection.py", router))


def test_publish_after_shutdown_agrees(router: str) -> None:
    """A callback still publishing at Ctrl-C (an action server's status) gets rclpy's RCLError, not Zenoh's."""
    assert_same(*run_both("after_shutdown.py", router))
