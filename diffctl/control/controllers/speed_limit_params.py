"""The per-axis speed limit parameters several ros2_controllers YAMLs share (mecanum_drive_controller's
`linear.x.*`, `linear.y.*`, `angular.z.*`): eight doubles per axis, NaN = not set, validated with control_toolbox's
`gt_eq_or_nan<>` / `lt_eq_or_nan<>`, and read into the SpeedLimits of math/speed_limiter.py."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from diffctl.control.controllers.param_decl import Check, ParamDecl
from diffctl.control.math.speed_limiter import SpeedLimits

_GE = (Check("control_filters::gt_eq_or_nan", (0.0,)),)
_LE = (Check("control_filters::lt_eq_or_nan", (0.0,)),)
FIELDS = ("max_velocity", "min_velocity", "max_acceleration", "max_deceleration", "max_acceleration_reverse",
          "max_deceleration_reverse", "max_jerk", "min_jerk")


def axis_decls(axis: str, rotational: bool = False) -> list[ParamDecl]:
    """`<axis>.max_velocity` … `<axis>.min_jerk`, with the YAML's descriptions (forward/reverse for linear axes,
    positive/negative for angular ones)."""
    ahead, back = ("positive", "negative") if rotational else ("forward", "reverse")
    texts = {
        "max_acceleration": f"Maximum acceleration in {ahead} direction.",
        "max_deceleration": f"Maximum deceleration in {ahead} direction.",
        "max_acceleration_reverse": f"Maximum acceleration in {back} direction. If not set, -max_acceleration will "
                                    "be used.",
        "max_deceleration_reverse": f"Maximum deceleration in {back} direction. If not set, -max_deceleration will "
                                    "be used.",
    }
    signs = {"max_velocity": _GE, "min_velocity": _LE, "max_acceleration": _GE, "max_deceleration": _LE,
             "max_acceleration_reverse": _LE, "max_deceleration_reverse": _GE, "max_jerk": _GE, "min_jerk": _LE}
    return [ParamDecl(f"{axis}.{f}", "double", math.nan, texts.get(f, ""), checks=signs[f]) for f in FIELDS]


def limits(values: Mapping[str, Any], axis: str) -> SpeedLimits:
    return SpeedLimits(**{f: values[f"{axis}.{f}"] for f in FIELDS})
