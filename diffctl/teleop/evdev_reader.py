"""Linux evdev game pads read directly from /dev/input/event* (struct input_event, EVIOC* ioctls).

No library and no display: the kernel's event interface is a stream of fixed-size records, and the
device's name, capabilities and axis ranges come from ioctls.
"""

from __future__ import annotations

import array
import errno
import fcntl
import os
import select
import struct
from dataclasses import dataclass, field
from pathlib import Path

from diffctl.errors import ConfigError, RuntimeFailure
from diffctl.teleop.joy_mapping import AxisRange
from diffctl.teleop.linux_input import AXIS_NAMES, BUTTON_NAMES, EV_ABS, EV_KEY, GAMEPAD_KEY_RANGE

INPUT_ROOT = Path("/dev/input")
# struct input_event { struct timeval time; __u16 type; __u16 code; __s32 value; } on 64-bit Linux.
INPUT_EVENT = struct.Struct("llHHi")
ABSINFO = struct.Struct("6i")  # value, minimum, maximum, fuzz, flat, resolution
KEY_MAX = 0x2FF
ABS_MAX = 0x3F

_IOC_READ = 2


def _ioc(direction: int, nr: int, size: int) -> int:
    return (direction << 30) | (size << 16) | (ord("E") << 8) | nr


def eviocgname(length: int) -> int:
    return _ioc(_IOC_READ, 0x06, length)


def eviocgkey(length: int) -> int:
    return _ioc(_IOC_READ, 0x18, length)


def eviocgbit(ev: int, length: int) -> int:
    return _ioc(_IOC_READ, 0x20 + ev, length)


def eviocgabs(axis: int) -> int:
    return _ioc(_IOC_READ, 0x40 + axis, ABSINFO.size)


def parse_events(buf: bytes) -> list[tuple[int, int, int]]:
    """(type, code, value) of each whole input_event record in `buf`."""
    n = len(buf) // INPUT_EVENT.size
    return [INPUT_EVENT.unpack_from(buf, i * INPUT_EVENT.size)[2:] for i in range(n)]


def _bits(fd: int, request: int, nbytes: int) -> set[int]:
    buf = array.array("B", bytes(nbytes))
    fcntl.ioctl(fd, request, buf, True)
    return {i * 8 + b for i, byte in enumerate(buf) for b in range(8) if byte >> b & 1}


@dataclass(frozen=True)
class DeviceInfo:
    path: str
    name: str
    buttons: tuple[int, ...] = ()
    axes: dict[int, AxisRange] = field(default_factory=dict)
    error: str | None = None

    @property
    def is_gamepad(self) -> bool:
        return any(b in GAMEPAD_KEY_RANGE for b in self.buttons)

    def describe(self) -> str:
        if self.error:
            return f"{self.path} ({self.error})"
        kind = "game pad" if self.is_gamepad else "not a game pad"
        return f"{self.path} '{self.name}' ({kind})"

    def __rich__(self) -> object:
        return devices_table([self])


def devices_table(devices: list[DeviceInfo]) -> object:
    from diffctl.console import table

    rows = []
    for d in devices:
        buttons = " ".join(BUTTON_NAMES[b] for b in d.buttons if b in BUTTON_NAMES)
        axes = " ".join(AXIS_NAMES.get(a, hex(a)) for a in d.axes)
        rows.append((d.path, d.error or d.name, "yes" if d.is_gamepad else "no", buttons, axes))
    return table("input devices", ["device", "name", "game pad", "buttons", "axes"], rows)


def _query(fd: int, path: str) -> DeviceInfo:
    name_buf = array.array("B", bytes(256))
    fcntl.ioctl(fd, eviocgname(len(name_buf)), name_buf, True)
    name = name_buf.tobytes().split(b"\0", 1)[0].decode(errors="replace")
    ev_types = _bits(fd, eviocgbit(0, 4), 4)
    keys = sorted(_bits(fd, eviocgbit(EV_KEY, KEY_MAX // 8 + 1), KEY_MAX // 8 + 1)) if EV_KEY in ev_types else []
    axes: dict[int, AxisRange] = {}
    if EV_ABS in ev_types:
        for code in sorted(_bits(fd, eviocgbit(EV_ABS, ABS_MAX // 8 + 1), ABS_MAX // 8 + 1)):
            buf = array.array("B", bytes(ABSINFO.size))
            fcntl.ioctl(fd, eviocgabs(code), buf, True)
            _, lo, hi, _, _, _ = ABSINFO.unpack(buf.tobytes())
            axes[code] = AxisRange(lo, hi)
    return DeviceInfo(path, name, tuple(keys), axes)


def _event_paths(root: Path) -> list[Path]:
    def num(p: Path) -> int:
        tail = p.name[len("event") :]
        return int(tail) if tail.isdigit() else 1 << 30

    return sorted(root.glob("event*"), key=num) if root.is_dir() else []


def list_devices(root: Path = INPUT_ROOT) -> list[DeviceInfo]:
    """Every /dev/input/event* device, with an error text for those that cannot be opened."""
    out = []
    for p in _event_paths(root):
        try:
            fd = os.open(p, os.O_RDONLY | os.O_NONBLOCK)
        except OSError as e:
            hint = " (add yourself to the 'input' group)" if e.errno == errno.EACCES else ""
            out.append(DeviceInfo(str(p), "", error=f"{e.strerror}{hint}"))
            continue
        try:
            out.append(_query(fd, str(p)))
        except OSError as e:
            out.append(DeviceInfo(str(p), "", error=f"not an evdev device: {e.strerror}"))
        finally:
            os.close(fd)
    return out


def present(devices: list[DeviceInfo], root: Path = INPUT_ROOT) -> str:
    if not root.is_dir():
        return f"no input devices present ({root} does not exist)"
    if not devices:
        return f"no input devices present in {root}"
    return "devices present: " + "; ".join(d.describe() for d in devices)


def find_device(spec: str | None = None, device_id: int = 0, root: Path = INPUT_ROOT) -> str:
    """The event device path for `spec` (a path, or a name substring), else the `device_id`-th game pad."""
    devices = list_devices(root)
    if spec:
        if "/" in spec:
            if any(d.path == spec and not d.error for d in devices) or Path(spec).exists():
                return spec
            raise ConfigError(f"no input device at {spec}; {present(devices, root)}", field="device")
        named = [d for d in devices if not d.error and spec.lower() in d.name.lower()]
        if named:
            return named[0].path
        raise ConfigError(f"no input device named like {spec!r}; {present(devices, root)}", field="device_name")
    pads = [d for d in devices if d.is_gamepad]
    if device_id < len(pads):
        return pads[device_id].path
    raise ConfigError(
        f"no game pad number {device_id} (found {len(pads)}); {present(devices, root)}",
        field="device_id",
        hint="plug one in, or pick one with --device /dev/input/eventN",
    )


class InputDevice:
    """An open evdev device: its axis ranges, current state, and a `read(timeout)` of pending events."""

    def __init__(self, path: str) -> None:
        try:
            self.fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
        except OSError as e:
            hint = "add yourself to the 'input' group" if e.errno == errno.EACCES else None
            raise ConfigError(f"cannot open input device: {e.strerror}", source=path, hint=hint) from None
        try:
            self.info = _query(self.fd, path)
        except OSError as e:
            os.close(self.fd)
            raise ConfigError(f"not an evdev input device: {e.strerror}", source=path) from None
        self.path = path
        self._pending = b""

    @property
    def axis_ranges(self) -> dict[int, AxisRange]:
        return dict(self.info.axes)

    def initial_events(self) -> list[tuple[int, int, int]]:
        """The device's current state as events (buttons already held, axes off-centre)."""
        events = [(EV_KEY, code, 1) for code in sorted(_bits(self.fd, eviocgkey(KEY_MAX // 8 + 1), KEY_MAX // 8 + 1))]
        for code in self.info.axes:
            buf = array.array("B", bytes(ABSINFO.size))
            fcntl.ioctl(self.fd, eviocgabs(code), buf, True)
            events.append((EV_ABS, code, ABSINFO.unpack(buf.tobytes())[0]))
        return events

    def read(self, timeout_s: float | None) -> list[tuple[int, int, int]]:
        """Events that arrive within `timeout_s` (an empty list on timeout)."""
        ready, _, _ = select.select([self.fd], [], [], timeout_s)
        if not ready:
            return []
        try:
            data = os.read(self.fd, INPUT_EVENT.size * 64)
        except BlockingIOError:
            return []
        except OSError as e:
            if e.errno == errno.ENODEV:
                raise RuntimeFailure(f"input device {self.path} disappeared (unplugged?)") from None
            raise
        buf = self._pending + data
        whole = len(buf) - len(buf) % INPUT_EVENT.size
        self._pending = buf[whole:]
        return parse_events(buf[:whole])

    def close(self) -> None:
        try:
            os.close(self.fd)
        except OSError:
            pass
