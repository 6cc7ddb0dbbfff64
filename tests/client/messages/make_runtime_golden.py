"""Regenerate data/rosidl_runtime_py_jazzy.json: the runtime program under upstream's rosidl_runtime_py (its
`jazzy` branch, a checkout named on the command line; it is not on PyPI) in the oracle venv, with the real
generated message classes.

    .venv/bin/python -m tests.client.messages.make_runtime_golden /path/to/rosidl_runtime_py
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from tests.client.messages.programs import PRELUDE
from tests.client.messages.runtime_program import PROGRAM
from tests.oracle import jazzy_venv

GOLDEN = Path(__file__).parent / "data" / "rosidl_runtime_py_jazzy.json"


def main() -> None:
    checkout = Path(sys.argv[1]).resolve()
    p = jazzy_venv.run_python(f"import sys; sys.path.insert(0, {str(checkout)!r})\n" + PRELUDE + PROGRAM)
    out = json.loads(next(line for line in reversed(p.stdout.splitlines()) if line.startswith("OBS"))[3:])
    GOLDEN.write_text(json.dumps(out, indent=1, ensure_ascii=False) + "\n")
    print(f"{GOLDEN}: {len(out)} observations")


if __name__ == "__main__":
    main()
