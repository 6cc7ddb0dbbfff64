"""key_teleop's rule, pure: the arrow keys seen in the last 0.4 s → (linear, angular) velocity.

A terminal reports a held key as repeats, not as a press and a release, so a key counts as held while its last
report is younger than 0.4 s. Up and down add ±1 forward, left and right ±1 turning (left positive); forward
is scaled by forward_rate, backward (and standing) by backward_rate, turning by rotation_rate.
"""

from __future__ import annotations

from dataclasses import dataclass

HELD_FOR_NS = 400_000_000
UP, DOWN, LEFT, RIGHT = "up", "down", "left", "right"
MOVES = {UP: (1, 0), DOWN: (-1, 0), LEFT: (0, 1), RIGHT: (0, -1)}


@dataclass(frozen=True)
class Rates:
    forward: float = 0.8
    backward: float = 0.5
    rotation: float = 1.0


def velocity(last_seen_ns: dict[str, int], now_ns: int, rates: Rates) -> tuple[float, float]:
    linear = angular = 0.0
    for key, seen in last_seen_ns.items():
        if now_ns - seen < HELD_FOR_NS:
            forward, turn = MOVES[key]
            linear += forward
            angular += turn
    linear *= rates.forward if linear > 0 else rates.backward
    return linear + 0.0, angular * rates.rotation + 0.0
