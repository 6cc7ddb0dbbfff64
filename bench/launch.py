"""Launcher benchmark: start 50 trivial processes, stop them, measure.

Metrics (budget): `launch_50_all_started_s` (≤ 0.5 s, from the first action to the last process started, as
the launcher logs it), `launch_50_all_reaped_s` (≤ 0.5 s, from SIGINT to the launcher's exit with every
process reaped), `launcher_rss_mb` (≤ 80 MB, the launcher's resident memory with 50 children). Also
`launch_50_wall_to_started_s`, from exec of `diffctl launch` (interpreter start-up included).
"""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
import uuid
from pathlib import Path

import psutil

COUNT = 50


def _wait_for(path: Path, pattern: str, proc: subprocess.Popen, timeout_s: float) -> re.Match[str]:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        m = re.search(pattern, path.read_text())
        if m:
            return m
        if proc.poll() is not None:
            raise RuntimeError(f"launcher exited with {proc.returncode}:\n{path.read_text()}")
        time.sleep(0.005)
    raise TimeoutError(f"no /{pattern}/ after {timeout_s} s:\n{path.read_text()}")


def _tagged(tag: str) -> list[psutil.Process]:
    out = []
    for p in psutil.process_iter():
        try:
            if p.status() != psutil.STATUS_ZOMBIE and p.environ().get("DIFFCTL_BENCH_TAG") == tag:
                out.append(p)
        except (psutil.NoSuchProcess, psutil.AccessDenied, psutil.ZombieProcess):
            continue
    return out


def run() -> dict:
    tag = uuid.uuid4().hex
    with tempfile.TemporaryDirectory(prefix="diffctl-bench-launch-") as tmp:
        work = Path(tmp)
        launch_file = work / "fifty.yaml"
        launch_file.write_text(
            "launch:\n" + "".join(f"- executable: {{name: p{i:02d}, cmd: 'sleep 600'}}\n" for i in range(COUNT))
        )
        out = work / "launcher.out"
        env = dict(os.environ, DIFFCTL_BENCH_TAG=tag)
        argv = [sys.executable, "-m", "diffctl", "launch", str(launch_file), "--no-router", "--no-color"]
        with open(out, "w") as sink:
            t_exec = time.monotonic()
            proc = subprocess.Popen(
                [*argv, "--log-dir", str(work / "logs")],
                stdout=sink,
                stderr=subprocess.STDOUT,
                stdin=subprocess.DEVNULL,
                env=env,
                start_new_session=True,
            )
            try:
                m = _wait_for(out, rf"all {COUNT} processes started in (\d+) ms", proc, 30)
                wall_started = time.monotonic() - t_exec
                launcher = psutil.Process(proc.pid)
                rss = 0
                for _ in range(5):  # the peak over 100 ms with all 50 children running
                    rss = max(rss, launcher.memory_info().rss)
                    time.sleep(0.02)
                t_stop = time.monotonic()
                proc.send_signal(signal.SIGINT)
                code = proc.wait(30)
                reaped = time.monotonic() - t_stop
                left = _tagged(tag)
            finally:
                if proc.poll() is None:
                    os.killpg(proc.pid, signal.SIGKILL)
                    proc.wait()
                for p in _tagged(tag):
                    p.kill()
        if code != 0 or left:
            raise RuntimeError(f"launcher exit code {code}, {len(left)} processes left:\n{out.read_text()}")
    return {
        "launch_50_all_started_s": round(int(m.group(1)) / 1000.0, 3),
        "launch_50_all_reaped_s": round(reaped, 3),
        "launcher_rss_mb": round(rss / 2**20, 1),
        "launch_50_wall_to_started_s": round(wall_started, 3),
    }


def main() -> None:
    from bench.budget import BUDGET, verdict

    metrics = run()
    for key, value in metrics.items():
        row = BUDGET.get(key)
        said = "" if row is None else f"  {verdict(value, row[0], row[1])} ({row[0]} {row[1]:g})"
        print(f"{key:32s} {value:>8}{said}")
    results = Path(__file__).parent / "results"
    results.mkdir(exist_ok=True)
    (results / "launch.json").write_text(json.dumps(metrics, indent=2) + "\n")


if __name__ == "__main__":
    main()
