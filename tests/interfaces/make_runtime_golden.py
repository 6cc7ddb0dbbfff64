"""Regenerate the golden files of upstream's pure-Python packages that are not on PyPI, run in the oracle venv
with the real generated message classes: data/rosidl_runtime_py_jazzy.json (rosidl_runtime_py's `jazzy`
branch) and data/point_cloud2_jazzy.json (common_interfaces' `jazzy` branch, sensor_msgs_py). Each argument
is a folder holding the upstream Python package (e.g. `git archive jazzy rosidl_runtime_py | tar -x`).

    .venv/bin/python -m tests.interfaces.make_runtime_golden /path/to/rosidl_runtime_py_src \
        /path/to/common_interfaces/sensor_msgs_py
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from tests.interfaces import point_cloud2_program, runtime_program
from tests.interfaces.programs import PRELUDE
from tests.oracle import jazzy_venv

DATA = Path(__file__).parent / "data"
GOLDEN = DATA / "rosidl_runtime_py_jazzy.json"
POINT_CLOUD2_GOLDEN = DATA / "point_cloud2_jazzy.json"


def _run(source: Path, program: str, golden: Path) -> None:
    p = jazzy_venv.run_python(f"import sys; sys.path.insert(0, {str(source.resolve())!r})\n" + PRELUDE + program)
    out = json.loads(next(line for line in reversed(p.stdout.splitlines()) if line.startswith("OBS"))[3:])
    golden.write_text(json.dumps(out, indent=1, ensure_ascii=False) + "\n")
    print(f"{golden}: {len(out)} observations")


def main() -> None:
    _run(Path(sys.argv[1]), runtime_program.PROGRAM, GOLDEN)
    if len(sys.argv) > 2:
        _run(Path(sys.argv[2]), point_cloud2_program.PROGRAM, POINT_CLOUD2_GOLDEN)


if __name__ == "__main__":
    main()
