"""Command lines of tf2_ros's tools, parsed as their C++ programs parse them (tf2_ros, branch jazzy):
static_transform_broadcaster_program.cpp's flags and old positional forms, tf2_echo.cpp's frames and rate.

Pure: no node, no bus. Errors carry the programs' own messages.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass

OLD_STYLE_WARNING = "Old-style arguments are deprecated; see --help for new-style arguments"

STATIC_USAGE = (
    "usage: static_transform_publisher [--x X] [--y Y] [--z Z] [--qx QX] [--qy QY] "
    "[--qz QZ] [--qw QW] [--roll ROLL] [--pitch PITCH] [--yaw YAW] --frame-id FRAME_ID "
    "--child-frame-id CHILD_FRAME_ID\n\n"
    "A command line utility for manually sending a static transform.\n\nIf no translation or"
    " orientation is provided, the identity transform will be published.\n\nThe translation offsets"
    " are in meters.\n\nThe rotation may be provided with roll, pitch, yaw euler angles in radians,"
    " or as a quaternion.\n\n"
    "required arguments:\n"
    "  --frame-id FRAME_ID parent frame\n"
    "  --child-frame-id CHILD_FRAME_ID child frame id\n\n"
    "optional arguments:\n"
    "  --x X                 x component of translation\n"
    "  --y Y                 y component of translation\n"
    "  --z Z                 z component of translation\n"
    "  --qx QX               x component of quaternion rotation\n"
    "  --qy QY               y component of quaternion rotation\n"
    "  --qz QZ               z component of quaternion rotation\n"
    "  --qw QW               w component of quaternion rotation\n"
    "  --roll ROLL           roll component Euler rotation\n"
    "  --pitch PITCH         pitch component Euler rotation\n"
    "  --yaw YAW             yaw component Euler rotation"
)

ECHO_USAGE = (
    "Usage: tf2_echo source_frame target_frame [echo_rate]\n\n"
    "This will echo the transform from the coordinate frame of the source_frame\n"
    "to the coordinate frame of the target_frame. \n"
    "Note: This is the transform to get data from target_frame into the source_frame.\n"
    "Default echo rate is 1 if echo_rate is not given.\n"
)

# std::stod / std::stof: the longest leading decimal, hex, inf or nan number; trailing text is ignored.
_NUMBER = re.compile(
    r"\s*[+-]?(?:0[xX](?:[0-9a-fA-F]+\.?[0-9a-fA-F]*|\.[0-9a-fA-F]+)(?:[pP][+-]?\d+)?"
    r"|(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf(?:inity)?|nan(?:\([0-9A-Za-z_]*\))?)",
    re.IGNORECASE,
)


class ArgsError(ValueError):
    """A command line the program refuses; str() is the program's message."""


def stod(text: str) -> tuple[float, int]:
    """(value, characters used) as std::stod converts `text`; ArgsError when nothing converts."""
    m = _NUMBER.match(text)
    if m is None:
        raise ArgsError(text)
    number = m.group(0).strip()
    if number.lower().lstrip("+-").startswith("0x"):
        sign = -1.0 if number.startswith("-") else 1.0
        value = sign * float.fromhex(number.lstrip("+-"))
    elif "nan" in number.lower():
        value = math.nan
    else:
        value = float(number)
    return value, m.end()


def quaternion_from_rpy(roll: float, pitch: float, yaw: float) -> tuple[float, float, float, float]:
    """tf2::Quaternion::setRPY (fixed axes: roll about X, then pitch about Y, then yaw about Z)."""
    hr, hp, hy = roll * 0.5, pitch * 0.5, yaw * 0.5
    cr, sr, cp, sp, cy, sy = math.cos(hr), math.sin(hr), math.cos(hp), math.sin(hp), math.cos(hy), math.sin(hy)
    return (
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
        cr * cp * cy + sr * sp * sy,
    )


@dataclass(frozen=True)
class StaticTransform:
    translation: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rotation: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)  # x, y, z, w
    frame_id: str = ""
    child_frame_id: str = ""
    help: bool = False
    old_style: bool = False  # positional arguments: the program warns that they are deprecated


_DOUBLE_FLAGS = {"--qx": "qx", "--qy": "qy", "--qz": "qz", "--qw": "qw", "--roll": "roll", "--pitch": "pitch",
                 "--yaw": "yaw", "--x": "x", "--y": "y", "--z": "z"}
_STRING_FLAGS = {"--frame-id": "frame_id", "--child-frame-id": "child_frame_id"}


def parse_static(args: list[str], warn: Callable[[str], None] | None = None) -> StaticTransform:
    """static_transform_publisher's arguments (ROS arguments already removed; no program name). `warn` gets
    the deprecation of the positional forms, at the point the program logs it (before their own errors)."""
    values: dict[str, float] = {"x": 0.0, "y": 0.0, "z": 0.0, "qx": 0.0, "qy": 0.0, "qz": 0.0, "qw": 1.0,
                                "roll": 0.0, "pitch": 0.0, "yaw": 0.0}
    frames = {"frame_id": "", "child_frame_id": ""}
    saw_frame = saw_quat = saw_rpy = saw_trans = help_ = False
    positional: list[str] = []

    def number(optname: str, text: str) -> float:
        try:
            return stod(text)[0]
        except ArgsError:
            raise ArgsError(f"Failed to parse {optname} argument as float") from None

    i = 0
    while i < len(args):
        opt = args[i]
        if opt in ("--help", "-h"):
            help_ = True
        elif opt in _DOUBLE_FLAGS or opt in _STRING_FLAGS:
            if i == len(args) - 1:
                raise ArgsError(f"Not enough arguments for {opt}")
            i += 1
            if opt in _STRING_FLAGS:
                frames[_STRING_FLAGS[opt]] = args[i]
                saw_frame = True
            else:
                key = _DOUBLE_FLAGS[opt]
                values[key] = number(opt, args[i])
                saw_quat |= key in ("qx", "qy", "qz", "qw")
                saw_rpy |= key in ("roll", "pitch", "yaw")
                saw_trans |= key in ("x", "y", "z")
        else:
            positional.append(opt)
        i += 1
    if help_:
        return StaticTransform(help=True)
    if saw_rpy and saw_quat:
        raise ArgsError("Cannot specify both quaternion and Euler rotations")
    rotation = (values["qx"], values["qy"], values["qz"], values["qw"])
    if saw_rpy:
        rotation = quaternion_from_rpy(values["roll"], values["pitch"], values["yaw"])
    old_style = len(positional) in (8, 9)
    if old_style:
        if warn is not None:
            warn(OLD_STYLE_WARNING)
        if saw_frame or saw_trans or saw_quat:
            raise ArgsError("Cannot specify both new-style (flags) and old-style (arguments)")
        values["x"], values["y"], values["z"] = (number(n, t) for n, t in zip(("x", "y", "z"), positional[:3],
                                                                             strict=True))
        if len(positional) == 8:
            yaw, pitch, roll = (number(n, t) for n, t in zip(("yaw", "pitch", "roll"), positional[3:6], strict=True))
            rotation = quaternion_from_rpy(roll, pitch, yaw)
            frames["frame_id"], frames["child_frame_id"] = positional[6], positional[7]
        else:
            q = [number(n, t) for n, t in zip(("qx", "qy", "qz", "qw"), positional[3:7], strict=True)]
            rotation = (q[0], q[1], q[2], q[3])
            frames["frame_id"], frames["child_frame_id"] = positional[7], positional[8]
    elif positional:
        raise ArgsError("Extra unparsed arguments on command-line")
    if frames["frame_id"] == "":
        raise ArgsError("Frame id must not be empty")
    if frames["child_frame_id"] == "":
        raise ArgsError("Child frame id must not be empty")
    return StaticTransform((values["x"], values["y"], values["z"]), rotation, frames["frame_id"],
                           frames["child_frame_id"], False, old_style)


@dataclass(frozen=True)
class EchoArgs:
    source_frame: str
    target_frame: str
    rate_hz: float = 1.0


class EchoUsage(ArgsError):
    """tf2_echo's usage text (exit code `code`)."""

    def __init__(self, message: str, code: int) -> None:
        super().__init__(message)
        self.code = code


def parse_echo(args: list[str]) -> EchoArgs:
    """tf2_echo's arguments: source_frame target_frame [echo_rate] (exit codes as the program's)."""
    if len(args) == 2:
        return EchoArgs(args[0], args[1])
    if len(args) == 3:
        bad = f"Failed to convert rate argument '{args[2]}' to a floating-point number"
        try:
            rate, used = stod(args[2])
        except ArgsError:
            raise EchoUsage(bad, 2) from None
        if used != len(args[2]):
            raise EchoUsage(bad, 3)
        return EchoArgs(args[0], args[1], rate)
    raise EchoUsage(ECHO_USAGE, 1)
