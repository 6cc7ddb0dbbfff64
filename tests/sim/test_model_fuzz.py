"""No model crashes the simulator: thousands of fuzzed SDF and URDF shapes are built and stepped in real PyBullet.

Hypothesis writes models the way odd real ones look: many links (past the 127 one PyBullet body holds), static
compounds of many shapes (past the 16 one PyBullet link holds, with meshes among them: the TurtleBot3 house
crashed createMultiBody so), degenerate and huge meshes, zero and negative sizes, zero masses and inertias,
zero axes. Each case must either run or be refused with a DescriptionError (one clear message); anything else,
and above all a dead process, fails. PyBullet runs in a child process (tests/sim/fuzz_worker.py) fed a batch
at a time, so a segfault is a failing case, named, not a dead test run.
"""

from __future__ import annotations

import json
import math
import random
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

WORKER = Path(__file__).resolve().parent / "fuzz_worker.py"
REPO = Path(__file__).resolve().parents[2]
BATCH = 40
BATCHES = 40  # 1600 cases

# Values as odd descriptions carry them: missing volume, negative, tiny, ordinary, huge.
LENGTHS = (0.0, -0.5, 1e-7, 0.05, 0.3, 1.0, 250.0, 1e5)
MASSES = (0.0, 1e-9, 0.2, 1.0, 40.0, 1e6, -1.0)
MOMENTS = (0.0, 1e-12, 1e-4, 0.1, 1.0, 1e5, -0.01)
COORDS = (0.0, 0.0, 0.1, -0.4, 2.0, 1e4)
ANGLES = (0.0, 0.0, 1.5707963, -0.3, 3.1415926)
AXES = ("0 0 1", "1 0 0", "0 1 0", "1 1 0")
ZERO_AXIS = "0 0 0"
SCALES = ("1 1 1", "0 1 1", "-1 1 1", "1e-6 1e-6 1e-6", "100 100 100")
LIMITS = ((-1.0, 1.0), (0.0, 0.0), (1.0, -1.0), (-1e16, 1e16))
ODD = 0.2  # the share of odd inertia and zero axes in a small model (a large one gets none: it would be refused)
SURFACES = (
    "",
    "<surface><friction><ode><mu>0</mu><mu2>0</mu2></ode></friction></surface>",
    "<surface><friction><ode><mu>100</mu></ode></friction></surface>",
)


def _obj_many(n: int) -> str:
    pts = [(math.cos(k * 0.618 * 6.283) * 0.3, math.sin(k * 0.618 * 6.283) * 0.3, (k % 97) / 97.0) for k in range(n)]
    verts = "".join(f"v {x:.5f} {y:.5f} {z:.5f}\n" for x, y, z in pts)
    faces = "".join(f"f {k} {k + 1} {k + 2}\n" for k in range(1, n - 1))
    return verts + faces


MESHES = {
    "empty.obj": "",
    "point.obj": "v 0 0 0\nf 1 1 1\n",
    "line.obj": "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
    "flat.obj": "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n",
    "tetra.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n",
    "huge.obj": "v -1e6 -1e6 0\nv 1e6 -1e6 0\nv 0 1e6 0\nv 0 0 1e6\nf 1 2 3\nf 1 2 4\nf 2 3 4\nf 1 3 4\n",
    "many.obj": _obj_many(4000),
    "noface.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\n",
    "empty.stl": "solid nothing\nendsolid nothing\n",
    "flat.stl": "solid f\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 2 0 0\nendloop\n"
    "endfacet\nendsolid f\n",
}
MESH_NAMES = sorted(MESHES)


def _geometry(r: random.Random, fmt: str, meshes: bool) -> str:
    kind = r.choice(("box", "sphere", "cylinder", "mesh", "mesh", "capsule") if meshes else ("box", "sphere"))
    c = r.choice
    if fmt == "urdf":
        if kind == "box":
            return f'<box size="{c(LENGTHS)} {c(LENGTHS)} {c(LENGTHS)}"/>'
        if kind == "sphere":
            return f'<sphere radius="{c(LENGTHS)}"/>'
        if kind in ("cylinder", "capsule"):
            return f'<cylinder radius="{c(LENGTHS)}" length="{c(LENGTHS)}"/>'
        return f'<mesh filename="{c(MESH_NAMES)}" scale="{c(SCALES)}"/>'
    if kind == "box":
        return f"<box><size>{c(LENGTHS)} {c(LENGTHS)} {c(LENGTHS)}</size></box>"
    if kind == "sphere":
        return f"<sphere><radius>{c(LENGTHS)}</radius></sphere>"
    if kind in ("cylinder", "capsule"):
        return f"<{kind}><radius>{c(LENGTHS)}</radius><length>{c(LENGTHS)}</length></{kind}>"
    return f"<mesh><uri>{c(MESH_NAMES)}</uri><scale>{c(SCALES)}</scale></mesh>"


def _pose(r: random.Random) -> tuple[str, str]:
    c = r.choice
    return f"{c(COORDS)} {c(COORDS)} {c(COORDS)}", f"{c(ANGLES)} {c(ANGLES)} {c(ANGLES)}"


def _inertial(r: random.Random, fmt: str, odd: float) -> str:
    if r.random() < odd / 2:
        return ""
    if r.random() >= odd:  # a possible body (zeros and extremes included), else anything at all
        m, d, off = r.choice([v for v in MASSES if v > 0]), [r.choice([v for v in MOMENTS if v >= 0])] * 3, 0.0
    else:
        m, d, off = r.choice(MASSES), [r.choice(MOMENTS) for _ in range(3)], r.choice((0.0, 0.0, 0.01, -0.5))
    xyz, rpy = _pose(r)
    if fmt == "urdf":
        return (
            f'<inertial><origin xyz="{xyz}" rpy="{rpy}"/><mass value="{m}"/><inertia ixx="{d[0]}" ixy="{off}" '
            f'ixz="0" iyy="{d[1]}" iyz="0" izz="{d[2]}"/></inertial>'
        )
    return (
        f"<inertial><pose>{xyz} {rpy}</pose><mass>{m}</mass><inertia><ixx>{d[0]}</ixx><ixy>{off}</ixy>"
        f"<iyy>{d[1]}</iyy><izz>{d[2]}</izz></inertia></inertial>"
    )


def _link(r: random.Random, fmt: str, name: str, shapes_max: int, odd: float, meshes: bool) -> str:
    parts = [_inertial(r, fmt, odd)]
    for kind in ("collision", "visual"):
        for k in range(r.randint(0, shapes_max)):
            xyz, rpy = _pose(r)
            g = _geometry(r, fmt, meshes)
            if fmt == "urdf":
                parts.append(f'<{kind}><origin xyz="{xyz}" rpy="{rpy}"/><geometry>{g}</geometry></{kind}>')
            else:
                surface = r.choice(SURFACES) if kind == "collision" else ""
                parts.append(
                    f"<{kind} name='{kind[0]}{k}'><pose>{xyz} {rpy}</pose><geometry>{g}</geometry>{surface}</{kind}>"
                )
    return f'<link name="{name}">{"".join(parts)}</link>'


def expand(fmt: str, size: str, static: bool, seed: int) -> dict:
    """One model from a small recipe: hypothesis draws (and shrinks) the recipe, a seeded generator the rest."""
    r = random.Random(seed)
    n_links = {"small": r.randint(1, 6), "many_links": r.randint(100, 140), "many_shapes": r.randint(1, 2)}[size]
    shapes_max = {"small": 3, "many_links": 1, "many_shapes": 60}[size]
    static = static and fmt == "sdf"
    odd = ODD if size != "many_links" else 0.0
    # (a large tree is about PyBullet's link capacity: its shapes are primitives, which build fast)
    links = [_link(r, fmt, f"l{i}", shapes_max, odd, size != "many_links") for i in range(n_links)]
    joints = []
    for i in range(1, n_links):
        parent = r.randint(0, i - 1)
        kind = r.choice(("fixed", "revolute", "continuous", "prismatic", "ball" if fmt == "sdf" else "floating"))
        xyz, rpy = _pose(r)
        axis, (lo, hi) = (ZERO_AXIS if r.random() < odd / 4 else r.choice(AXES)), r.choice(LIMITS)
        if fmt == "urdf":
            joints.append(
                f'<joint name="j{i}" type="{kind}"><parent link="l{parent}"/><child link="l{i}"/>'
                f'<origin xyz="{xyz}" rpy="{rpy}"/><axis xyz="{axis}"/>'
                f'<limit lower="{lo}" upper="{hi}" effort="10" velocity="1"/></joint>'
            )
        elif r.random() < 0.9:  # now and then a link is left as a tree of its own
            joints.append(
                f"<joint name='j{i}' type='{kind}'><parent>l{parent}</parent><child>l{i}</child><pose>{xyz} "
                f"{rpy}</pose><axis><xyz>{axis}</xyz><limit><lower>{lo}</lower><upper>{hi}</upper></limit></axis>"
                "</joint>"
            )
    body = "".join(links) + "".join(joints)
    if fmt == "urdf":
        text = f'<robot name="fuzz">{body}</robot>'
    else:
        text = (
            f'<sdf version="1.8"><model name="fuzz"><static>{str(static).lower()}</static>'
            f"<pose>0 0 0.5 0 0 0</pose>{body}</model></sdf>"
        )
    files = {name: content for name, content in MESHES.items() if name in text}
    return {"format": fmt, "text": text, "files": files, "steps": 5}


RECIPES = st.tuples(
    st.sampled_from(["sdf", "sdf", "urdf"]),
    st.sampled_from(["small"] * 38 + ["many_links", "many_shapes"]),
    st.booleans(),
    st.integers(0, 2**32 - 1),
)


class Worker:
    """The child process, restarted after it dies."""

    def __init__(self, directory: Path) -> None:
        self.directory = directory
        self.proc: subprocess.Popen | None = None

    def _start(self) -> subprocess.Popen:
        return subprocess.Popen(
            [sys.executable, str(WORKER), str(self.directory)],
            cwd=REPO,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            text=True,
        )

    def run(self, cases: list[dict]) -> list[dict]:
        results: list[dict] = []
        for i, case in enumerate(cases):  # one at a time: a case's text can outgrow a pipe's buffer
            if self.proc is None or self.proc.poll() is not None:
                self.proc = self._start()
            assert self.proc.stdin is not None and self.proc.stdout is not None
            self.proc.stdin.write(json.dumps({"id": i, **case}) + "\n")
            self.proc.stdin.flush()
            while True:
                line = self.proc.stdout.readline()
                if not line:
                    code = self.proc.wait()
                    raise AssertionError(
                        f"the simulator process died (exit {code}) building/stepping this {case['format']} model "
                        f"(files: {sorted(case['files'])}):\n{case['text'][:4000]}"
                    )
                msg = json.loads(line)
                if not msg.get("started"):
                    results.append(msg)
                    break
        return results

    def close(self) -> None:
        if self.proc is not None:
            self.proc.kill()
            self.proc.wait()
            for stream in (self.proc.stdin, self.proc.stdout):
                if stream is not None:
                    stream.close()


@pytest.fixture(scope="module")
def worker(tmp_path_factory: pytest.TempPathFactory):
    w = Worker(tmp_path_factory.mktemp("fuzz"))
    yield w
    w.close()


@settings(
    max_examples=BATCHES,
    deadline=None,
    derandomize=True,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.function_scoped_fixture],
)
@given(recipes=st.lists(RECIPES, min_size=BATCH, max_size=BATCH))
def test_fuzzed_models_run_or_are_refused_never_crash(worker: Worker, recipes: list[tuple]) -> None:
    cases = [expand(*recipe) for recipe in recipes]
    for case, result in zip(cases, worker.run(cases), strict=True):
        assert result["outcome"] in ("ok", "refused"), f"{result['detail']}\n{case['text'][:4000]}"
