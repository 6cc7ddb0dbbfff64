"""Installed from a wheel, run from another directory: `diffctl launch sim_control --print` resolves every file."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

from tests.conftest import REPO

pytestmark = pytest.mark.slow


def test_wheel_install_resolves_every_file(tmp_path: Path) -> None:
    wheels = tmp_path / "wheels"
    r = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q", "-w",
                        str(wheels), str(REPO)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    (wheel,) = wheels.glob("diffctl-*.whl")

    # A fresh venv whose only diffctl is the wheel; the dependencies come from the dev venv's site-packages
    # as a plain path (its editable-install hook is not processed), so nothing is downloaded.
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True, timeout=120)
    py = venv / "bin" / "python"
    site = Path(subprocess.run([str(py), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                               capture_output=True, text=True, check=True).stdout.strip())
    (site / "dev_deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    r = subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "-q", "--target", str(site),
                        str(wheel)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr

    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "DIFFCTL_PROJECT_DIR")}
    where = subprocess.run([str(py), "-c", "import diffctl; print(diffctl.__file__)"], cwd=elsewhere, env=env,
                           capture_output=True, text=True, check=True).stdout.strip()
    assert where.startswith(str(site)), f"imported {where}, not the wheel"

    def run(*args: str) -> str:
        r = subprocess.run([str(py), "-m", "diffctl", *args], cwd=elsewhere, env=env, capture_output=True,
                           text=True, timeout=120)
        assert r.returncode == 0, f"{args}: {r.stdout}\n{r.stderr}"
        return r.stdout

    share = site / "diffctl" / "share"
    shares: dict[str, str] = {}

    def share_of(pkg: str) -> str:
        if pkg not in shares:
            shares[pkg] = run("pkg", "prefix", pkg, "--share").strip()
        return shares[pkg]

    # --print describes without performing substitutions (as ros2 launch --print): a file of a package shows as
    # FindPackageShare(pkg='P') + '/rel', resolved here as the launch would, through P's share directory.
    for launch in ("sim_control", "sim_control.launch.py", "sim", "mock_control", "teleop"):
        out = run("launch", launch, "--print", "--no-color")
        assert str(REPO) not in out, f"{launch} resolved files from the checkout:\n{out}"
        out = re.sub(r"FindPackageShare\(pkg='(\w+)'\) \+ '", lambda m: "'" + share_of(m[1]), out)
        files = re.findall(r"(?<![>\w])(/[^\s'\",]+\.(?:yaml|sdf|world|rviz))", out)
        assert files or launch == "teleop", out  # teleop's files are its presets, chosen at run time
        for path in files:
            assert Path(path).is_relative_to(share) and Path(path).is_file(), f"{launch}: {path} not in the wheel"
