"""Run one program from tests/client/programs under the real rclpy (Fast DDS, the oracle venv) and under
diffctl's client library (on a real router), and return what each printed.

Each program prints one JSON list of `[label, observation...]` as its last stdout line; its log lines go to
stderr, where the console format and the QoS warnings are compared too.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from tests.oracle import jazzy_venv

PROGRAMS = Path(__file__).parent / "programs"
REPO = Path(__file__).resolve().parents[2]
_STAMP = re.compile(r"^\[(DEBUG|INFO|WARN|ERROR|FATAL)\] \[\d+\.\d{9}\] ")


@dataclass
class Run:
    observations: list
    stderr: str

    def log_lines(self) -> list[str]:
        """Console log lines with their stamps removed (rcl's own lines left out)."""
        return [_STAMP.sub(r"[\1] ", line) for line in self.stderr.splitlines()
                if _STAMP.match(line) and "] [rcl]:" not in line]


def _parse(stdout: str, stderr: str) -> list:
    for line in reversed(stdout.splitlines()):
        if line.startswith("["):
            return json.loads(line)
    raise AssertionError(f"the program printed no observations:\n{stdout}\n{stderr}")


def run_oracle(name: str, timeout_s: float = 90) -> Run:
    p = jazzy_venv.run_python((PROGRAMS / name).read_text(), timeout_s=timeout_s)
    return Run(_parse(p.stdout, p.stderr), p.stderr)


def run_ours(name: str, router: str, timeout_s: float = 90, args: list[str] | None = None) -> Run:
    env = {**os.environ, "DIFFCTL_ROUTER": router, "PYTHONUNBUFFERED": "1"}
    p = subprocess.run([sys.executable, str(PROGRAMS / name), *(args or [])], env=env, cwd=REPO,
                       capture_output=True, text=True, timeout=timeout_s)
    if p.returncode != 0:
        raise AssertionError(f"{name} failed under diffctl ({p.returncode}):\n{p.stdout}\n{p.stderr}")
    return Run(_parse(p.stdout, p.stderr), p.stderr)


def run_both(name: str, router: str) -> tuple[Run, Run]:
    """The oracle's run and ours at the same time (each program is mostly waiting on its middleware)."""
    with ThreadPoolExecutor(max_workers=1) as pool:
        oracle = pool.submit(run_oracle, name)
        ours = run_ours(name, router)
        return oracle.result(), ours


def assert_same(oracle: Run, ours: Run) -> None:
    """Every observation equal, label by label (a mismatch lists both sides)."""
    diffs = [f"  {a[0]}:\n    rclpy:   {a[1:]}\n    diffctl: {b[1:]}"
             for a, b in zip(oracle.observations, ours.observations, strict=True) if a != b]
    assert not diffs, "observations differ:\n" + "\n".join(diffs)
