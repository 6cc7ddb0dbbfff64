"""A user's smoke test of the tutorial car, as `diffctl test --init` writes it: wall time of `diffctl test` on it
(`smoke_test_wall_s`: launch, controllers active, drive 2 s of sim time, assert, shut down) and of 8 copies
under `-j 2` (`smoke_tests_parallel_wall_s`), each on its own router and domain. Run: `python -m bench testing`.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
COPIES = 8


def _workspace(root: Path) -> Path:
    pkg = root / "ws" / "src" / "diffctl_demo"
    (pkg / "launch").mkdir(parents=True)
    shutil.copytree(REPO / "config", pkg / "config")
    shutil.copy(REPO / "launch" / "sim_control.launch.py", pkg / "launch")
    (pkg / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>diffctl_demo</name><version>0.1.0</version>'
        '<description>car</description><maintainer email="me@example.com">me</maintainer>'
        "<license>Apache-2.0</license><buildtool_depend>ament_cmake</buildtool_depend>"
        "<export><build_type>ament_cmake</build_type></export></package>\n"
    )
    (pkg / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.8)\nproject(diffctl_demo)\nfind_package(ament_cmake REQUIRED)\n"
        "install(DIRECTORY launch config DESTINATION share/${PROJECT_NAME})\nament_package()\n"
    )
    return root / "ws"


def _timed(argv: list[str], cwd: Path) -> float:
    t0 = time.monotonic()
    r = subprocess.run(argv, cwd=cwd, capture_output=True, text=True, timeout=300, start_new_session=True)
    took = time.monotonic() - t0
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(argv[3:])} failed:\n{r.stdout[-3000:]}\n{r.stderr[-2000:]}")
    return took


def run() -> dict:
    diffctl = [sys.executable, "-m", "diffctl"]
    with tempfile.TemporaryDirectory(prefix="bench-smoke-") as tmp:
        ws = _workspace(Path(tmp))
        subprocess.run([*diffctl, "test", "--init", "diffctl_demo"], cwd=ws, check=True, capture_output=True)
        test_dir = ws / "src" / "diffctl_demo" / "test"
        one = test_dir / "test_diffctl_demo_smoke.launch.py"
        _timed([*diffctl, "test", str(one)], ws)  # warm the file caches once
        single = min(_timed([*diffctl, "test", str(one)], ws) for _ in range(2))
        copies = []
        for i in range(COPIES):
            copy = Path(tmp) / "copies" / f"test_smoke_{i}.launch.py"
            copy.parent.mkdir(exist_ok=True)
            shutil.copy(one, copy)
            copies.append(str(copy))
        parallel = _timed([*diffctl, "test", "-j", "2", *copies], ws)
    return {"smoke_test_wall_s": round(single, 2), "smoke_tests_parallel_wall_s": round(parallel, 2)}
