"""Rumble through a Linux event device (linux/input.h force feedback), as joy_linux_node drives it.

The node sets the device's gain to full, uploads one FF_RUMBLE effect (EVIOCSFF, which gives it an id), and
then asks for it to be played (an EV_FF event whose code is the effect's id) on every pass of its loop; a
JoyFeedback rumble entry changes the effect's strong (id 0) or weak (other ids) magnitude, uploaded on the next
pass.
"""

from __future__ import annotations

import fcntl
import os
import struct

EV_FF = 0x15
FF_RUMBLE = 0x50
FF_GAIN = 0x60
TYPE_RUMBLE = 1
# struct input_event on 64-bit Linux: struct timeval, __u16 type, __u16 code, __s32 value
INPUT_EVENT = struct.Struct("=qqHHi")
# struct ff_effect: type, id, direction, trigger {button, interval}, replay {length, delay}, then the union
# (8-byte aligned, 32 bytes: ff_periodic_effect's pointer), whose ff_rumble_effect is strong, weak magnitude.
FF_EFFECT = struct.Struct("=HhHHHHH2xHH28x")
EVIOCSFF = (1 << 30) | (FF_EFFECT.size << 16) | (ord("E") << 8) | 0x80


def event(kind: int, code: int, value: int) -> bytes:
    return INPUT_EVENT.pack(0, 0, kind, code & 0xFFFF, value)


def gain_event(percent: int = 100) -> bytes:
    return event(EV_FF, FF_GAIN, 0xFFFF * percent // 100)


def magnitude(intensity: float) -> int:
    """A JoyFeedback intensity as the effect's 16-bit magnitude: 2^15 × intensity, truncated as C converts."""
    value = float(1 << 15) * intensity
    return int(value) & 0xFFFF if value == value and abs(value) < 1 << 31 else 0


class Rumble:
    """One rumble effect on an open event device."""

    def __init__(self, fd: int) -> None:
        self.fd = fd
        self.effect_id = -1
        self.strong = self.weak = 0
        self.changed = False

    def effect(self) -> bytearray:
        return bytearray(FF_EFFECT.pack(FF_RUMBLE, self.effect_id, 0, 0, 0, 1000, 0, self.strong, self.weak))

    def upload(self) -> None:
        buf = self.effect()
        try:
            fcntl.ioctl(self.fd, EVIOCSFF, buf, True)
        except OSError:
            return  # the node does not look at the answer either: the next play request just finds no effect
        self.effect_id = FF_EFFECT.unpack(bytes(buf))[1]

    def set_feedback(self, entries: list[tuple[int, int, float]]) -> None:
        """(type, id, intensity) of a JoyFeedbackArray."""
        for kind, ident, intensity in entries:
            if kind != TYPE_RUMBLE:
                continue
            if ident == 0:
                self.strong = magnitude(intensity)
            else:
                self.weak = magnitude(intensity)
            self.changed = True

    def play(self) -> None:
        """Ask for the effect (OSError when the device is gone); upload a changed one."""
        os.write(self.fd, event(EV_FF, self.effect_id, 3))
        if self.changed:
            self.upload()
            self.changed = False
