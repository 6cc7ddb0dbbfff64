"""`diffctl teleop joy` against a virtual game pad made with /dev/uinput (skipped, with the reason, without it).

Also the missing-device error, which needs no device at all.
"""

from __future__ import annotations

import fcntl
import os
import struct
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from diffctl.teleop.linux_input import AXES, BUTTONS, EV_ABS, EV_KEY, EV_SYN, SYN_REPORT
from tests.probe import Probe

UINPUT = Path("/dev/uinput")


def _iow(nr: int, size: int) -> int:
    return (1 << 30) | (size << 16) | (ord("U") << 8) | nr


def _ior(nr: int, size: int) -> int:
    return (2 << 30) | (size << 16) | (ord("U") << 8) | nr


UI_DEV_CREATE = (ord("U") << 8) | 1
UI_DEV_DESTROY = (ord("U") << 8) | 2
UI_DEV_SETUP = _iow(3, 92)  # struct uinput_setup: input_id (4 x u16), name[80], ff_effects_max u32
UI_ABS_SETUP = _iow(4, 28)  # struct uinput_abs_setup: u16 code (+2 pad), struct input_absinfo (6 x s32)
UI_SET_EVBIT = _iow(100, 4)
UI_SET_KEYBIT = _iow(101, 4)
UI_SET_ABSBIT = _iow(103, 4)
UI_GET_SYSNAME_64 = _ior(44, 64)
EVENT = struct.Struct("llHHi")
PAD_NAME = "diffctl virtual pad"


def uinput_unavailable() -> str | None:
    if not UINPUT.exists():
        return "/dev/uinput does not exist here (no uinput module, or a container without it)"
    if not os.access(UINPUT, os.W_OK):
        return "/dev/uinput is not writable by this user"
    return None


@pytest.fixture
def virtual_pad() -> Iterator[tuple[int, str]]:
    """A uinput game pad with LB/RB and a left stick; yields (uinput fd, its /dev/input/eventN path)."""
    fd = os.open(UINPUT, os.O_WRONLY | os.O_NONBLOCK)
    try:
        fcntl.ioctl(fd, UI_SET_EVBIT, EV_KEY)
        fcntl.ioctl(fd, UI_SET_EVBIT, EV_ABS)
        for name in ("A", "B", "LB", "RB"):
            fcntl.ioctl(fd, UI_SET_KEYBIT, BUTTONS[name])
        for name in ("LEFTX", "LEFTY"):
            fcntl.ioctl(fd, UI_SET_ABSBIT, AXES[name])
            fcntl.ioctl(fd, UI_ABS_SETUP, struct.pack("HH6i", AXES[name], 0, 0, -32768, 32767, 16, 128, 0))
        setup = struct.pack("4H80sI", 0x03, 0x045E, 0x028E, 1, PAD_NAME.encode(), 0)
        fcntl.ioctl(fd, UI_DEV_SETUP, setup)
        fcntl.ioctl(fd, UI_DEV_CREATE)
        buf = bytearray(64)
        fcntl.ioctl(fd, UI_GET_SYSNAME_64, buf, True)
        sysname = bytes(buf).split(b"\0", 1)[0].decode()
        sys_dir = Path("/sys/devices/virtual/input") / sysname
        path = None
        deadline = time.monotonic() + 3.0
        while path is None and time.monotonic() < deadline:
            nodes = [p.name for p in sys_dir.glob("event*")]
            if nodes and Path("/dev/input", nodes[0]).exists():
                path = str(Path("/dev/input", nodes[0]))
            else:
                time.sleep(0.05)
        if path is None:
            pytest.skip(reason=f"uinput created {sysname}, but no /dev/input node appeared (no udev/devtmpfs here)")
        yield fd, path
    finally:
        try:
            fcntl.ioctl(fd, UI_DEV_DESTROY)
        except OSError:
            pass
        os.close(fd)


def emit(fd: int, *events: tuple[int, int, int]) -> None:
    for ev_type, code, value in (*events, (EV_SYN, SYN_REPORT, 0)):
        os.write(fd, EVENT.pack(0, 0, ev_type, code, value))


@pytest.mark.skipif(uinput_unavailable() is not None, reason=uinput_unavailable() or "")
def test_virtual_pad_drives_over_the_bus(router: str, procs, virtual_pad: tuple[int, str]) -> None:
    fd, path = virtual_pad
    topic = "/diffbot_base_controller/cmd_vel"
    node = Probe("uinput_probe")
    got: list[tuple[float, float]] = []
    node.create_subscription(
        topic, "geometry_msgs/msg/TwistStamped", lambda m: got.append((m.twist.linear.x, m.twist.angular.z))
    )
    try:
        proc = procs.diffctl("teleop", "joy", "--device", path, "--joy-config", "xbox")
        deadline = time.monotonic() + 10
        while not any(e.node == "teleop_twist_joy_node" for e in node.graph.publishers(topic)):
            assert time.monotonic() < deadline and proc.poll() is None, proc.stdout.read() if proc.poll() else ""
            time.sleep(0.05)
        emit(fd, (EV_KEY, BUTTONS["LB"], 1), (EV_ABS, AXES["LEFTY"], -32768))
        deadline = time.monotonic() + 5
        while not any(x > 0.6 for x, _ in got) and time.monotonic() < deadline:
            time.sleep(0.02)
        assert any(x == pytest.approx(0.7) for x, _ in got)
        emit(fd, (EV_KEY, BUTTONS["LB"], 0))
        time.sleep(0.5)
        assert got[-1] == (0.0, 0.0)
    finally:
        node.close()
    assert procs.stop(proc) == 0


def test_missing_device_is_exit_2_listing_devices() -> None:
    r = subprocess.run(
        [sys.executable, "-m", "diffctl", "teleop", "joy", "--device", "/dev/input/event99"],
        capture_output=True,
        text=True,
        timeout=30,
        env={**os.environ, "DIFFCTL_ROUTER": "tcp/127.0.0.1:9"},
    )
    err = " ".join(r.stderr.split())
    assert r.returncode == 2, err
    assert "no input device at /dev/input/event99;" in err
    assert "devices present" in err or "no input devices present" in err
