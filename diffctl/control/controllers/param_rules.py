"""generate_parameter_library validators the shared table (param_decl) does not know, for the controllers that
use them: `size_gt<>`, `size_lt<>`, `fixed_size<>`, `subset_of<>`, `element_bounds<>`, and controller-specific
rules registered by name (e.g. `joint_trajectory_controller::command_interface_type_combinations`).

`RuleCheck` is a `param_decl.Check`, so the same table declares, validates and describes these parameters.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.control.controllers.param_decl import Check

# rule name → function(value) → reason or None
CUSTOM: dict[str, Callable[[Any], str | None]] = {}


class RuleCheck(Check):
    def reason(self, value: Any) -> str | None:
        kind, args = self.kind, self.args
        if kind == "size_gt":
            return None if len(value) > args[0] else f"{value!r} must have more than {args[0]} entries"
        if kind == "size_lt":
            return None if len(value) < args[0] else f"{value!r} must have fewer than {args[0]} entries"
        if kind == "fixed_size":
            return None if len(value) == args[0] else f"{value!r} has {len(value)} entries, expected {args[0]}"
        if kind == "subset_of":
            bad = [v for v in value if v not in args[0]]
            return f"{value!r}: {bad[0]!r} is not one of {list(args[0])}" if bad else None
        if kind == "element_bounds":
            bad = [v for v in value if not args[0] <= v <= args[1]]
            return f"{value!r} contains {bad[0]!r}: every entry must be within [{args[0]!r}, {args[1]!r}]" \
                if bad else None
        if kind in CUSTOM:
            return CUSTOM[kind](value)
        return super().reason(value)
