"""The oracle venv `.venv-jazzy`: ROS 2 Jazzy's real rclpy (Fast DDS) and message packages from PyPI.

`make jazzy-oracle` builds it (a dependency of `make test`). Programs run there in a clean environment:
the venv's own prefix as AMENT_PREFIX_PATH (rclpy finds its RMW there), its wheels' shared libraries on
LD_LIBRARY_PATH (what ros_wheels_bootstrapper would re-exec the interpreter for), Fast DDS on loopback
only, a ROS_DOMAIN_ID of this test process's own, no PYTHONPATH (never diffctl's overlay) and `-I`.

    run_python(code, env=None, timeout_s=60) -> CompletedProcess (raises with the output on failure)
    start_python(code, procs, env=None) -> Popen   # long-lived, killed by the `procs` fixture
    share(pkg) -> Path                             # <venv>/share/<pkg> (.msg, .idl, .json of each type)
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
VENV = REPO / ".venv-jazzy"
PYTHON = VENV / "bin" / "python"


class OracleMissing(RuntimeError):
    pass


def python() -> Path:
    if not PYTHON.exists():
        raise OracleMissing(f"{VENV} is missing: run `make jazzy-oracle` (a dependency of `make test`)")
    return PYTHON


def site_packages() -> Path:
    return VENV / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages"


def share(pkg: str) -> Path:
    return VENV / "share" / pkg


def env(extra: dict[str, str] | None = None) -> dict[str, str]:
    python()
    libs = [str(VENV / "lib"), *sorted(str(p) for p in site_packages().glob("ros_*.libs"))]
    e = {
        "PATH": os.environ.get("PATH", "/usr/bin:/bin"),
        "HOME": os.environ.get("HOME", "/tmp"),
        "LANG": "C.UTF-8",
        "AMENT_PREFIX_PATH": str(VENV),
        "LD_LIBRARY_PATH": os.pathsep.join(libs),
        "_ROS_WHEELS_BOOTSTRAP_COMPLETE": "1",
        "RMW_IMPLEMENTATION": "rmw_fastrtps_cpp",
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
        "ROS_LOCALHOST_ONLY": "1",
        # One domain per test process: helpers and CI runs on the same machine do not hear each other.
        "ROS_DOMAIN_ID": str(os.getpid() % 100 + 100),
        "PYTHONUNBUFFERED": "1",
        "PYTHONDONTWRITEBYTECODE": "1",
    }
    if extra:
        e.update(extra)
    return e


def run_python(code: str, env_extra: dict[str, str] | None = None, timeout_s: float = 60,
               check: bool = True) -> subprocess.CompletedProcess[str]:
    """Run `code` in the oracle's interpreter; on failure (check) raise with its output."""
    with tempfile.TemporaryDirectory() as cwd:
        p = subprocess.run([str(python()), "-I", "-c", code], env=env(env_extra), cwd=cwd, capture_output=True,
                           text=True, timeout=timeout_s)
    if check and p.returncode != 0:
        raise AssertionError(f"oracle program failed ({p.returncode}):\n{p.stdout}\n{p.stderr}")
    return p


def start_python(code: str, procs, env_extra: dict[str, str] | None = None) -> subprocess.Popen:
    """A long-lived oracle program, in its own process group, killed by the `procs` fixture."""
    return procs.start([str(python()), "-I", "-c", code], env=env(env_extra), cwd=tempfile.gettempdir())
