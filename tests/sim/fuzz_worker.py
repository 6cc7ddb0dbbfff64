"""A child process that builds and steps fuzzed models in PyBullet, one per input line, so that a crash of the
process (a segfault inside PyBullet) is seen by the test as a failing case instead of killing the test run.

Protocol (JSON lines): in `{"id", "format": "sdf"|"urdf", "text", "files": {name: text}, "steps"}`; out
`{"id", "started": true}` before the work, then `{"id", "outcome": "ok"|"refused"|"error", "detail"}`.
"refused" is a DescriptionError (one clear message, as the simulator reports bad input); "error" is anything
else, which the simulator would die of.
"""

from __future__ import annotations

import json
import math
import os
import sys
import traceback
from pathlib import Path

from diffctl.description.model import Physics
from diffctl.description.robot_files import parse_description
from diffctl.errors import DescriptionError
from diffctl.sim.world import PhysicsWorld


def run_case(case: dict, directory: Path, world: PhysicsWorld) -> tuple[str, str]:
    for name, text in case.get("files", {}).items():
        path = directory / name
        if not path.is_file():  # the same name is the same file in every case: converted and checked once
            path.write_text(text)
    try:
        model = parse_description(case["text"], source=f"case{case['id']}.{case['format']}", base_dir=directory)
    except DescriptionError as e:
        return "refused", str(e)
    try:
        entity = world.add_model(model)
    except DescriptionError as e:
        return "refused", str(e)
    try:
        for _ in range(case.get("steps", 10)):
            world.step()
        pose = entity.pose()
        if not model.static and not all(math.isfinite(v) for v in (*pose.xyz, *pose.quat)):
            return "ok", "non-finite pose"  # diverged physics is not a crash; reported for information
        return "ok", ""
    finally:
        world.remove(model.name)


def main() -> None:
    # The protocol keeps the real stdout; whatever PyBullet's C code prints goes to stderr instead.
    out = os.fdopen(os.dup(1), "w")
    os.dup2(2, 1)
    directory = Path(sys.argv[1])  # the test's temporary folder: mesh files are written there once
    world = PhysicsWorld(Physics())  # one client for every case (connecting costs more than most cases)
    for line in sys.stdin:
        case = json.loads(line)
        print(json.dumps({"id": case["id"], "started": True}), file=out, flush=True)
        try:
            outcome, detail = run_case(case, directory, world)
        except Exception:
            outcome, detail = "error", traceback.format_exc(limit=6)
        print(json.dumps({"id": case["id"], "outcome": outcome, "detail": detail}), file=out, flush=True)


if __name__ == "__main__":
    main()
