"""`python -m diffctl.demo_nodes PACKAGE EXECUTABLE [args…]`: run one demo node with ROS arguments as given."""

from __future__ import annotations

import importlib
import sys

from diffctl.demo_nodes import PROGRAMS


def main() -> None:
    if len(sys.argv) < 3 or (sys.argv[1], sys.argv[2]) not in PROGRAMS:
        names = ", ".join(f"{p} {e}" for p, e in PROGRAMS)
        print(f"usage: python -m diffctl.demo_nodes PACKAGE EXECUTABLE [args]; one of: {names}", file=sys.stderr)
        sys.exit(2)
    module_name, function = PROGRAMS[(sys.argv[1], sys.argv[2])].split(":")
    sys.argv = [sys.argv[2], *sys.argv[3:]]  # as the installed program sees its own command line
    module = importlib.import_module(f"diffctl.demo_nodes.{module_name}")
    sys.exit(getattr(module, function)())


if __name__ == "__main__":
    main()
