"""joy_node and joy_linux_node as real processes on a real router, reading a joystick made of a FIFO of
`struct js_event` records: what they publish on /joy, joy_linux's /diagnostics and rumble writes, a device that
goes away and comes back, and a bad parameter refused."""

from __future__ import annotations

import os
import struct
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import pytest

from tests.joy import fifo
from tests.joy.fifo import AXIS, BUTTON
from tests.probe import probe
from tests.waiting import wait_for

pytestmark = pytest.mark.slow


class Joys:
    """/joy as received."""

    def __init__(self, p: Any) -> None:
        self.lock = threading.Lock()
        self.got: list[Any] = []
        self.at = time.monotonic()
        p.create_subscription("/joy", "sensor_msgs/msg/Joy", self.on)

    def on(self, m: Any) -> None:
        with self.lock:
            self.got.append(m)
            self.at = time.monotonic()

    def quiet_for(self, seconds: float) -> bool:
        with self.lock:
            return time.monotonic() - self.at > seconds

    def seen(self, pred) -> bool:
        with self.lock:
            return any(pred(list(m.axes), list(m.buttons)) for m in self.got)

    def last(self) -> Any:
        with self.lock:
            return self.got[-1]


def test_joy_node_reads_the_joystick_sdl_numbers(router: str, procs, tmp_path: Path) -> None:
    js = fifo.make(tmp_path / "js")
    p = probe("joy_probe")
    joys = Joys(p)
    node = procs.diffctl("run", "joy", "joy_node", "--ros-args", "-p", "deadzone:=0.1", "-p", "autorepeat_rate:=50.0",
                         env={**os.environ, "SDL_JOYSTICK_DEVICE": f"{tmp_path / 'absent'}:{js}"})
    fd = None
    try:
        # device_id 0 is the first device SDL_JOYSTICK_DEVICE lists that can be opened: ours
        fd = fifo.open_writer(js, lambda: node.poll() is None)
        fifo.write(fd, *fifo.initial_state(4, [0, 20000]))
        assert wait_for(lambda: joys.seen(lambda a, b: len(a) == 2 and len(b) == 4), timeout_s=30)
        m = joys.last()
        assert m.header.frame_id == "joy"
        assert list(m.axes)[1] == pytest.approx(-(20000 - 3276.7) / (0.9 * 32767), abs=1e-6)  # initial value kept
        fifo.write(fd, (BUTTON, 2, 1), (AXIS, 0, -32767))
        assert wait_for(lambda: joys.seen(lambda a, b: b == [0, 0, 1, 0] and a[0] == 1.0), timeout_s=30)
        os.close(fd)  # the writer goes: end of file, the device is gone and nothing is published
        fd = None
        assert wait_for(lambda: joys.quiet_for(0.5), timeout_s=30)
        with joys.lock:
            joys.got.clear()
        fd = fifo.open_writer(js, lambda: node.poll() is None)  # looked for again every second
        fifo.write(fd, *fifo.initial_state(1, [0]))
        assert wait_for(lambda: joys.seen(lambda a, b: len(a) == 1 and b == [0]), timeout_s=30)  # a new message
    finally:
        if fd is not None:
            os.close(fd)
        p.close()
    assert procs.stop(node) == 0
    out = node.stdout.read()
    assert f"Opened joystick: {js}.  deadzone: 0.100000" in out, out


def test_joy_linux_node_publishes_diagnoses_and_rumbles(router: str, procs, tmp_path: Path) -> None:
    js, ff = fifo.make(tmp_path / "js0"), fifo.make(tmp_path / "ff")
    ff_fd = os.open(ff, os.O_RDONLY | os.O_NONBLOCK)  # the node's rumble writes land here
    p = probe("joy_linux_probe")
    joys = Joys(p)
    diagnostics: list[Any] = []
    p.create_subscription("/diagnostics", "diagnostic_msgs/msg/DiagnosticArray", diagnostics.append)
    node = procs.diffctl("run", "joy_linux", "joy_linux_node", "--ros-args", "-p", f"dev:={js}",
                         "-p", f"dev_ff:={ff}", "-p", "autorepeat_rate:=0.0", "-p", "coalesce_interval:=0.05")
    fd = None
    try:
        fd = fifo.open_writer(js, lambda: node.poll() is None)
        fifo.write(fd, *fifo.initial_state(3, [12000, 0]))
        assert wait_for(lambda: joys.seen(lambda a, b: a == [0.0, 0.0] and b == [0, 0, 0]), timeout_s=30)
        fifo.write(fd, (BUTTON, 1, 1))
        assert wait_for(lambda: joys.seen(lambda a, b: b == [0, 1, 0]), timeout_s=30)
        count = len(joys.got)
        fifo.write(fd, (AXIS, 0, -32767), (AXIS, 1, 32767))  # within one coalescing interval: one message
        assert wait_for(lambda: joys.seen(lambda a, b: a == [1.0, -1.0]), timeout_s=30)
        assert len(joys.got) == count + 1

        def statuses(message: str) -> list[Any]:
            return [s for array in list(diagnostics) for s in array.status
                    if s.name == "joy_node: Joystick Driver Status" and s.message == message]

        def status() -> Any:
            found = statuses("OK")
            return found[-1] if found else None

        assert wait_for(lambda: status() is not None, timeout_s=30)
        values = {kv.key: kv.value for kv in status().values}
        assert (status().hardware_id, values["topic"], values["device"], values["dead zone"]) == \
            ("none", "/joy", str(js), "0.05")
        assert (values["autorepeat rate (Hz)"], values["coalesce interval (s)"], values["sticky buttons"]) == \
            ("0", "0.05", "False")

        # rumble: full gain once, then a play request (EV_FF, the effect's id, 3 times) on every pass; a FIFO
        # takes no effect upload, so the id stays -1
        record = struct.Struct("=qqHHi")
        rumble = bytearray()
        assert wait_for(lambda: len(rumble) >= 3 * record.size, timeout_s=30,
                        every=lambda: rumble.extend(_drain(ff_fd)))
        writes = [record.unpack_from(rumble, i)[2:] for i in range(0, len(rumble) - record.size + 1, record.size)]
        assert writes[0] == (0x15, 0x60, 0xFFFF)
        assert set(writes[1:]) == {(0x15, 0xFFFF, 3)}

        closed = len(statuses("Joystick not open."))
        os.close(fd)  # the writer goes: the device is lost, and opened again
        fd = None
        assert wait_for(lambda: len(statuses("Joystick not open.")) > closed, timeout_s=30)  # noticed, reported
        fd = fifo.open_writer(js, lambda: node.poll() is None)
        fifo.write(fd, *fifo.initial_state(1, []))
        assert wait_for(lambda: joys.seen(lambda a, b: a == [] and b == [0]), timeout_s=30)  # a new message
    finally:
        if fd is not None:
            os.close(fd)
        os.close(ff_fd)
        p.close()
    assert procs.stop(node) == 0
    out = node.stdout.read()
    assert f"Opened joystick: {js}. deadzone_: 0.050000." in out, out
    assert "Connection to joystick device lost unexpectedly. Will reopen." in out, out


def _drain(fd: int) -> bytes:
    try:
        return os.read(fd, 1 << 16)
    except BlockingIOError:
        return b""


def test_bad_parameter_is_refused_with_its_value(router: str) -> None:
    r = subprocess.run([sys.executable, "-m", "diffctl", "run", "joy", "joy_node", "--ros-args", "-p", "deadzone:=1.5"],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2, r.stderr
    assert "deadzone" in r.stderr and "1.5" in r.stderr and "between 0.0 and 1.0" in r.stderr
