"""The Linux joystick API (linux/joystick.h): /dev/input/jsN devices, their js_event records and ioctls.

A joystick device is a stream of 8-byte `struct js_event` records; on open the kernel first replays the whole
state as events flagged JS_EVENT_INIT. Its name, counts and the input codes behind each axis and button come
from ioctls, which only a real joystick answers: a FIFO or a pty carrying the same records reads the same way,
without them.
"""

from __future__ import annotations

import array
import errno
import fcntl
import os
import select
import stat
import struct
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

INPUT_ROOT = Path("/dev/input")
# struct js_event { __u32 time; __s16 value; __u8 type; __u8 number; }
JS_EVENT = struct.Struct("=IhBB")
JS_EVENT_BUTTON = 0x01
JS_EVENT_AXIS = 0x02
JS_EVENT_INIT = 0x80

ABS_CNT = 0x40
KEY_MAX = 0x2FF
BTN_MISC = 0x100


def _ior(nr: int, size: int) -> int:
    return (2 << 30) | (size << 16) | (ord("j") << 8) | nr


JSIOCGAXES = _ior(0x11, 1)
JSIOCGBUTTONS = _ior(0x12, 1)
JSIOCGAXMAP = _ior(0x32, ABS_CNT)
JSIOCGBTNMAP = _ior(0x34, 2 * (KEY_MAX - BTN_MISC + 1))


def jsiocgname(length: int) -> int:
    return _ior(0x13, length)


@dataclass(frozen=True)
class JsEvent:
    time_ms: int
    value: int
    type: int
    number: int

    @property
    def is_init(self) -> bool:
        return bool(self.type & JS_EVENT_INIT)

    @property
    def kind(self) -> int:
        """JS_EVENT_BUTTON or JS_EVENT_AXIS (the init flag taken off); anything else is unknown."""
        return self.type & ~JS_EVENT_INIT

    def pack(self) -> bytes:
        return JS_EVENT.pack(self.time_ms & 0xFFFFFFFF, self.value, self.type, self.number)


def pack_events(events: Iterable[tuple[int, int, int]], time_ms: int = 0) -> bytes:
    """(type, number, value) triples as the kernel writes them."""
    return b"".join(JsEvent(time_ms, value, kind, number).pack() for kind, number, value in events)


class DeviceLost(Exception):
    """The device went away (unplugged, or the writer of a FIFO closed it)."""


@dataclass(frozen=True)
class Identity:
    """What the ioctls tell: None throughout for a file that is not a joystick (a FIFO, a pty)."""

    name: str | None
    axes: int | None
    buttons: int | None
    axis_codes: tuple[int, ...] | None  # the ABS_* code behind each axis number
    button_codes: tuple[int, ...] | None  # the BTN_*/KEY_* code behind each button number


def _ioctl_bytes(fd: int, request: int, size: int) -> bytes | None:
    buf = array.array("B", bytes(size))
    try:
        fcntl.ioctl(fd, request, buf, True)
    except OSError:
        return None
    return buf.tobytes()


def identify(fd: int) -> Identity:
    raw_name = _ioctl_bytes(fd, jsiocgname(128), 128)
    name = raw_name.split(b"\0", 1)[0].decode(errors="replace") if raw_name is not None else None
    n_axes = _ioctl_bytes(fd, JSIOCGAXES, 1)
    n_buttons = _ioctl_bytes(fd, JSIOCGBUTTONS, 1)
    axes = n_axes[0] if n_axes is not None else None
    buttons = n_buttons[0] if n_buttons is not None else None
    axmap = _ioctl_bytes(fd, JSIOCGAXMAP, ABS_CNT)
    btnmap = _ioctl_bytes(fd, JSIOCGBTNMAP, 2 * (KEY_MAX - BTN_MISC + 1))
    axis_codes = tuple(axmap[:axes]) if axmap is not None and axes is not None else None
    button_codes = (tuple(struct.unpack(f"={buttons}H", btnmap[: 2 * buttons]))
                    if btnmap is not None and buttons is not None else None)
    return Identity(name, axes, buttons, axis_codes, button_codes)


class Joystick:
    """An open joystick device: `read(timeout_s)` gives the whole records that arrived."""

    def __init__(self, path: str) -> None:
        # Non-blocking: opening a FIFO must not wait for its writer, and reads never stall the loop.
        self.fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
        self.path = path
        try:
            self.identity = identify(self.fd)
        except BaseException:
            os.close(self.fd)
            raise
        self._partial = b""

    def fileno(self) -> int:
        return self.fd

    def read(self, timeout_s: float | None) -> list[JsEvent]:
        """The records that arrive within `timeout_s` (none on timeout); DeviceLost when the device is gone."""
        ready, _, _ = select.select([self.fd], [], [], timeout_s)
        if not ready:
            return []
        try:
            data = os.read(self.fd, JS_EVENT.size * 64)
        except BlockingIOError:
            return []
        except OSError as e:
            if e.errno in (errno.ENODEV, errno.EIO, errno.EBADF):
                raise DeviceLost(f"{self.path}: {e.strerror}") from None
            raise
        if not data:
            raise DeviceLost(f"{self.path}: end of file")
        data = self._partial + data
        whole = len(data) - len(data) % JS_EVENT.size
        self._partial = data[whole:]
        return [JsEvent(*JS_EVENT.unpack_from(data, i)) for i in range(0, whole, JS_EVENT.size)]

    def close(self) -> None:
        try:
            os.close(self.fd)
        except OSError:
            pass


def joystick_paths(root: Path = INPUT_ROOT) -> list[str]:
    """/dev/input/js0, js1, … in number order."""
    def number(p: Path) -> int:
        tail = p.name[2:]
        return int(tail) if tail.isdigit() else 1 << 30

    if not root.is_dir():
        return []
    return [str(p) for p in sorted(root.glob("js*"), key=number)]


def is_character_device(path: str) -> bool:
    try:
        return stat.S_ISCHR(os.stat(path).st_mode)
    except OSError:
        return False


def device_name(path: str) -> str | None:
    """The device's name (JSIOCGNAME), or None when it cannot be opened or does not say."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    except OSError:
        return None
    try:
        raw = _ioctl_bytes(fd, jsiocgname(128), 128)
    finally:
        os.close(fd)
    return raw.split(b"\0", 1)[0].decode(errors="replace") if raw is not None else None
