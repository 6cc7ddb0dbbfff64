"""Run the same small program under the real generated classes (the oracle venv) and under diffctl's.

A program calls `obs(label, lambda: expr)` for each thing a user can observe; the result is `["ok", repr]`
or `["raise", exception type, message]`, printed as one JSON object at exit. `slot(t)` describes a
rosidl_parser.definition type structurally (its repr is an object address).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from tests.oracle import jazzy_venv

REPO = Path(__file__).resolve().parents[2]
OVERLAY = REPO / "diffctl" / "overlay"

PRELUDE = r'''
import array, atexit, copy, json, sys
import numpy
_out = {}
def obs(label, fn):
    try:
        v = fn()
        _out[label] = ["ok", v if isinstance(v, (bool, int, str, type(None))) else repr(v)]
    except Exception as e:
        _out[label] = ["raise", type(e).__name__, str(e)]
def slot(t):
    d = {"class": type(t).__name__}
    for a in ("typename", "maximum_size", "size", "name", "namespaces"):
        if hasattr(t, a):
            v = getattr(t, a)
            d[a] = list(v) if isinstance(v, (list, tuple)) else v
    if hasattr(t, "value_type"):
        d["value_type"] = slot(t.value_type)
    return d
def kind(v):
    if isinstance(v, numpy.ndarray):
        return ["ndarray", str(v.dtype), list(v.shape), v.flags.writeable]
    if isinstance(v, array.array):
        return ["array", v.typecode]
    if isinstance(v, list):
        return ["list", [type(x).__name__ for x in v[:2]]]
    return [type(v).__name__]
atexit.register(lambda: print("\nOBS" + json.dumps(_out)))
'''


def _parse(stdout: str, stderr: str) -> dict:
    for line in reversed(stdout.splitlines()):
        if line.startswith("OBS"):
            return json.loads(line[3:])
    raise AssertionError(f"the program printed no observations:\n{stdout}\n{stderr}")


def ours_env(extra: dict[str, str] | None = None) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "AMENT_", "COLCON_", "DIFFCTL_WORK"))}
    env["PYTHONPATH"] = str(OVERLAY)
    env.update(extra or {})
    return env


def run_ours(code: str, env: dict[str, str] | None = None, timeout_s: float = 60) -> dict:
    with tempfile.TemporaryDirectory() as cwd:
        p = subprocess.run([sys.executable, "-c", PRELUDE + code], env=ours_env(env), cwd=cwd,
                           capture_output=True, text=True, timeout=timeout_s)
    if p.returncode != 0:
        raise AssertionError(f"program failed under diffctl ({p.returncode}):\n{p.stdout}\n{p.stderr}")
    return _parse(p.stdout, p.stderr)


def run_oracle(code: str, env: dict[str, str] | None = None, timeout_s: float = 60) -> dict:
    p = jazzy_venv.run_python(PRELUDE + code, env, timeout_s)
    return _parse(p.stdout, p.stderr)


def assert_same(ours: dict, oracle: dict) -> None:
    assert ours.keys() == oracle.keys()
    diffs = {k: {"diffctl": ours[k], "rosidl": oracle[k]} for k in oracle if ours[k] != oracle[k]}
    assert not diffs, json.dumps(diffs, indent=1)
