"""teleop_twist_keyboard's key bindings and speed keys as a pure state machine (no terminal, no bus).

Bindings are the original's: `u i o / j k l / m , .` move (k or any other key stops), shift gives the
holonomic set, `t`/`b` move along z, `q/z` scale both speeds by ±10 %, `w/x` linear only, `e/c` angular
only. Arrow keys are accepted as `i , j l` for people who reach for them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from diffctl.errors import ParameterError

# key → (x, y, z, th) direction multipliers, as in teleop_twist_keyboard.py.
MOVE_BINDINGS: dict[str, tuple[int, int, int, int]] = {
    "i": (1, 0, 0, 0),
    "o": (1, 0, 0, -1),
    "j": (0, 0, 0, 1),
    "l": (0, 0, 0, -1),
    "u": (1, 0, 0, 1),
    ",": (-1, 0, 0, 0),
    ".": (-1, 0, 0, 1),
    "m": (-1, 0, 0, -1),
    "O": (1, -1, 0, 0),
    "I": (1, 0, 0, 0),
    "J": (0, 1, 0, 0),
    "L": (0, -1, 0, 0),
    "U": (1, 1, 0, 0),
    "<": (-1, 0, 0, 0),
    ">": (-1, -1, 0, 0),
    "M": (-1, 1, 0, 0),
    "t": (0, 0, 1, 0),
    "b": (0, 0, -1, 0),
    "UP": (1, 0, 0, 0),
    "DOWN": (-1, 0, 0, 0),
    "LEFT": (0, 0, 0, 1),
    "RIGHT": (0, 0, 0, -1),
}

# key → (linear factor, angular factor).
SPEED_BINDINGS: dict[str, tuple[float, float]] = {
    "q": (1.1, 1.1),
    "z": (0.9, 0.9),
    "w": (1.1, 1.0),
    "x": (0.9, 1.0),
    "e": (1.0, 1.1),
    "c": (1.0, 0.9),
}

QUIT_KEYS = ("\x03", "\x04")  # Ctrl-C, Ctrl-D

_ESCAPES = {
    "\x1b[A": "UP",
    "\x1b[B": "DOWN",
    "\x1b[C": "RIGHT",
    "\x1b[D": "LEFT",
    "\x1bOA": "UP",
    "\x1bOB": "DOWN",
    "\x1bOC": "RIGHT",
    "\x1bOD": "LEFT",
}

HELP = """\
Reading from the keyboard and publishing to {topic} ({kind})
---------------------------
Moving around:
   u    i    o
   j    k    l
   m    ,    .

For Holonomic mode (strafing), hold down the shift key:
---------------------------
   U    I    O
   J    K    L
   M    <    >

t : up (+z)
b : down (-z)
arrow keys : i , j l

anything else : stop

q/z : increase/decrease max speeds by 10%
w/x : increase/decrease only linear speed by 10%
e/c : increase/decrease only angular speed by 10%

CTRL-C to quit
"""


def split_keys(text: str) -> list[str]:
    """Key tokens from raw terminal input: single characters, arrow escape sequences as UP/DOWN/LEFT/RIGHT."""
    keys: list[str] = []
    i = 0
    while i < len(text):
        seq = text[i : i + 3]
        if seq in _ESCAPES:
            keys.append(_ESCAPES[seq])
            i += 3
        else:
            keys.append(text[i])
            i += 1
    return keys


@dataclass(frozen=True)
class KeyboardParams:
    speed_m_s: float = 0.5
    turn_rad_s: float = 1.0
    speed_limit_m_s: float = 5.0
    turn_limit_rad_s: float = 10.0

    def __post_init__(self) -> None:
        for name, value in (
            ("speed", self.speed_m_s),
            ("turn", self.turn_rad_s),
            ("speed_limit", self.speed_limit_m_s),
            ("turn_limit", self.turn_limit_rad_s),
        ):
            limit = name.endswith("_limit")  # a limit may be infinite: none
            if not isinstance(value, (int, float)) or isinstance(value, bool) or math.isnan(value) or value < 0 \
                    or (not limit and math.isinf(value)):
                raise ParameterError(f"{value!r} invalid; valid: a finite number >= 0", field=name)
        if self.speed_m_s > self.speed_limit_m_s:
            raise ParameterError(f"{self.speed_m_s} exceeds speed_limit {self.speed_limit_m_s}", field="speed")
        if self.turn_rad_s > self.turn_limit_rad_s:
            raise ParameterError(f"{self.turn_rad_s} exceeds turn_limit {self.turn_limit_rad_s}", field="turn")


class KeyboardTeleop:
    """The current speeds and direction; `press(key)` updates them as teleop_twist_keyboard does."""

    def __init__(self, params: KeyboardParams) -> None:
        self.params = params
        self.speed_m_s = float(params.speed_m_s)
        self.turn_rad_s = float(params.turn_rad_s)
        self.direction: tuple[int, int, int, int] = (0, 0, 0, 0)

    def press(self, key: str) -> bool:
        """Apply one key; False when it asks to quit."""
        if key in QUIT_KEYS:
            return False
        if key in MOVE_BINDINGS:
            self.direction = MOVE_BINDINGS[key]
        elif key in SPEED_BINDINGS:
            lin, ang = SPEED_BINDINGS[key]
            # Capped so a held `q` cannot wind the speed up to something absurd.
            self.speed_m_s = min(self.speed_m_s * lin, self.params.speed_limit_m_s)
            self.turn_rad_s = min(self.turn_rad_s * ang, self.params.turn_limit_rad_s)
        else:
            self.direction = (0, 0, 0, 0)
        return True

    def velocity(self) -> tuple[float, float, float, float]:
        """(linear x, linear y, linear z in m/s, angular z in rad/s) of the current command."""
        x, y, z, th = self.direction
        return (x * self.speed_m_s, y * self.speed_m_s, z * self.speed_m_s, th * self.turn_rad_s)

    def status(self) -> str:
        vx, vy, vz, wz = self.velocity()
        return (
            f"speed {self.speed_m_s:.2f} m/s  turn {self.turn_rad_s:.2f} rad/s  "
            f"| cmd x {vx:+.2f} y {vy:+.2f} z {vz:+.2f} yaw {wz:+.2f}"
        )
