"""What a system plugin gets from the simulator, and what it must offer back (reset, close)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from diffctl.description.model import Plugin
from diffctl.errors import DescriptionError
from diffctl.sim.log import Logger
from diffctl.sim.stepper import Stepper
from diffctl.sim.transport import SimTransport


@dataclass
class PluginContext:
    stepper: Stepper
    transport: SimTransport | None  # None when the world is driven without a bus (tests, benchmarks)
    log: Logger
    world_name: str


class SystemPlugin:
    """A Gazebo system attached to one model."""

    def reset(self) -> None:
        """The world was reset: back to the state at spawn."""

    def close(self) -> None:
        """The model is removed or the sim stops: undeclare everything."""


def float_param(
    plugin: Plugin, tag: str, default: float | None, *, source: str, positive: bool = False
) -> float | None:
    """A plugin's numeric parameter, with the value quoted when it is not a finite number."""
    text = plugin.get(tag)
    if text is None:
        return default
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value) or (positive and value <= 0):
        raise DescriptionError(
            f"plugin {plugin.name!r}: <{tag}> {text!r} is not a {'positive ' if positive else ''}finite number",
            source=source or None,
            field=f"plugin {plugin.filename}: {tag}",
        )
    return value


def rate_period_ns(rate_hz: float, step_ns: int) -> int:
    """A task period for `rate_hz`, never shorter than one physics step."""
    return max(step_ns, round(1e9 / rate_hz))


def bool_param(plugin: Plugin, tag: str, default: bool, *, source: str) -> bool:
    """A plugin's boolean parameter (true/false/1/0, as SDF writes them), with a bad value quoted."""
    text = plugin.get(tag)
    if text is None:
        return default
    value = text.strip().lower()
    if value in ("true", "1"):
        return True
    if value in ("false", "0"):
        return False
    raise DescriptionError(
        f"plugin {plugin.name!r}: <{tag}> {text!r} is not a boolean",
        source=source or None,
        field=f"plugin {plugin.filename}: {tag}",
        hint="valid: true, false, 1, 0",
    )
