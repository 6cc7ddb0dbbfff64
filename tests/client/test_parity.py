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
KNOWN_ABSENT = {"rclpy._rclpy_pybind11", "rclpy._rclpy_pybind11.service_introspection", "rclpy._dummy"}


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


# Every module's names, each with where its object was defined (or its type, for plain values).
_NAMES_PROGRAM = """
import importlib, json, pkgutil, types
import rclpy
out = {}
for name in ["rclpy"] + sorted(m.name for m in pkgutil.walk_packages(rclpy.__path__, "rclpy.")):
    if name.rsplit(".", 1)[-1].startswith("_"):
        continue
    try:
        module = importlib.import_module(name)
    except ImportError:
        continue
    out[name] = {n: "module" if isinstance(o, types.ModuleType) else getattr(o, "__module__", None) or type(o).__name__
                 for n, o in vars(module).items() if not n.startswith("_")}
print(json.dumps(out))
"""
# rclpy's logging filters as classes: diffctl's logger applies once/skip_first/throttle itself (same keywords,
# same results) and does not expose the classes.
_NAMES_NOT_PROVIDED = {"rclpy.impl.rcutils_logger": {"CallerId", "LoggingFilter", "Once", "SkipFirst", "Throttle",
                                                     "get_filters_from_kwargs"}}


def test_every_public_name_of_the_wheel_exists() -> None:
    """Each module has the names rclpy's defines (classes, functions, constants, the enums and infos its binding
    adds, such as QoSSubscriptionEventType or HIDDEN_NODE_PREFIX); names a module merely imports are left out."""
    import json

    real = json.loads(jazzy_venv.run_python(_NAMES_PROGRAM).stdout.splitlines()[-1])
    p = subprocess.run([sys.executable, "-c", _NAMES_PROGRAM], capture_output=True, text=True, timeout=60,
                       env={**os.environ, "PYTHONPATH": str(OVERLAY)})
    assert p.returncode == 0, p.stderr
    ours = json.loads(p.stdout.splitlines()[-1])

    def defined_here(module: str, name: str, where: str) -> bool:
        if name == "TYPE_CHECKING" or name.startswith("g_"):  # typing's flag; rclpy's module-private globals
            return False
        return where == module or where.startswith("rclpy._rclpy_pybind11") or where in ("str", "int", "float")

    missing = {m: sorted(n for n, where in names.items() if defined_here(m, n, where) and n not in ours.get(m, {})
                         and n not in _NAMES_NOT_PROVIDED.get(m, set()))
               for m, names in real.items()}
    assert {m: names for m, names in missing.items() if names} == {}
