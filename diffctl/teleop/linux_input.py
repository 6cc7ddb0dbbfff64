"""Linux input-event codes (linux/input-event-codes.h) and the names diffctl gives game pad controls.

Names follow SDL's game controller (what ROS 2 Jazzy's `joy` node uses) with PlayStation and joystick
aliases. The kernel names the top face button BTN_NORTH == BTN_X and the left one BTN_WEST == BTN_Y;
drivers disagree on which physical button that is, so `X`/`Y` here are the kernel's codes.
Numeric button and axis parameters are read in SDL's order, as teleop_twist_joy configs on Jazzy are.
"""

from __future__ import annotations

EV_SYN = 0x00
EV_KEY = 0x01
EV_ABS = 0x03
SYN_REPORT = 0
SYN_DROPPED = 3

BUTTONS: dict[str, int] = {
    # SDL game controller names (Xbox layout)
    "A": 0x130,
    "B": 0x131,
    "X": 0x133,
    "Y": 0x134,
    "LB": 0x136,
    "RB": 0x137,
    "LT": 0x138,
    "RT": 0x139,
    "BACK": 0x13A,
    "START": 0x13B,
    "GUIDE": 0x13C,
    "LSTICK": 0x13D,
    "RSTICK": 0x13E,
    "DPAD_UP": 0x220,
    "DPAD_DOWN": 0x221,
    "DPAD_LEFT": 0x222,
    "DPAD_RIGHT": 0x223,
    # PlayStation names
    "CROSS": 0x130,
    "CIRCLE": 0x131,
    "TRIANGLE": 0x133,
    "SQUARE": 0x134,
    "L1": 0x136,
    "R1": 0x137,
    "L2": 0x138,
    "R2": 0x139,
    "SELECT": 0x13A,
    "PS": 0x13C,
    "L3": 0x13D,
    "R3": 0x13E,
    # Joysticks (BTN_JOYSTICK range), e.g. the Logitech Attack 3
    "TRIGGER": 0x120,
    "THUMB": 0x121,
    "THUMB2": 0x122,
    "TOP": 0x123,
    "TOP2": 0x124,
    "PINKIE": 0x125,
    "BASE": 0x126,
    "BASE2": 0x127,
    "BASE3": 0x128,
    "BASE4": 0x129,
    "BASE5": 0x12A,
    "BASE6": 0x12B,
}

AXES: dict[str, int] = {
    "LEFTX": 0x00,  # ABS_X
    "LEFTY": 0x01,  # ABS_Y
    "TRIGGERLEFT": 0x02,  # ABS_Z
    "RIGHTX": 0x03,  # ABS_RX
    "RIGHTY": 0x04,  # ABS_RY
    "TRIGGERRIGHT": 0x05,  # ABS_RZ
    "THROTTLE": 0x06,
    "RUDDER": 0x07,
    "DPADX": 0x10,  # ABS_HAT0X
    "DPADY": 0x11,  # ABS_HAT0Y
}

# ROS 2 Jazzy `joy` (SDL game controller) index order, for numeric parameters.
SDL_BUTTON_ORDER = (
    "A",
    "B",
    "X",
    "Y",
    "BACK",
    "GUIDE",
    "START",
    "LSTICK",
    "RSTICK",
    "LB",
    "RB",
    "DPAD_UP",
    "DPAD_DOWN",
    "DPAD_LEFT",
    "DPAD_RIGHT",
)
SDL_AXIS_ORDER = ("LEFTX", "LEFTY", "RIGHTX", "RIGHTY", "TRIGGERLEFT", "TRIGGERRIGHT")

# A device is a game pad / joystick when it reports one of these keys (BTN_JOYSTICK, BTN_GAMEPAD ranges).
GAMEPAD_KEY_RANGE = range(0x120, 0x140)

BUTTON_NAMES: dict[int, str] = {}
for _name, _code in BUTTONS.items():
    BUTTON_NAMES.setdefault(_code, _name)
AXIS_NAMES: dict[int, str] = {code: name for name, code in AXES.items()}
