"""The evdev reader's pure parts: record parsing, ioctl numbers, device listing and the missing-device error."""

from __future__ import annotations

from pathlib import Path

import pytest

from diffctl.errors import ConfigError
from diffctl.teleop import evdev_reader as ev


def test_input_event_records_and_partial_reads() -> None:
    raw = ev.INPUT_EVENT.pack(1, 2, 3, 1, -32768) + ev.INPUT_EVENT.pack(1, 3, 0, 0, 0)
    assert ev.parse_events(raw) == [(3, 1, -32768), (0, 0, 0)]
    assert ev.parse_events(raw[:30]) == [(3, 1, -32768)]


def test_ioctl_numbers_match_linux_input_h() -> None:
    # Values of the C macros on x86-64/arm64, as compiled from <linux/input.h>.
    assert ev.eviocgname(256) == 0x81004506
    assert ev.eviocgabs(0x01) == 0x80184541
    assert ev.eviocgbit(0, 4) == 0x80044520
    assert ev.eviocgkey(96) == 0x80604518


def test_missing_device_lists_what_is_present(tmp_path: Path) -> None:
    (tmp_path / "event0").write_bytes(b"")  # a file, not an evdev node: listed with its error
    devices = ev.list_devices(tmp_path)
    assert len(devices) == 1 and devices[0].error and "not an evdev device" in devices[0].error
    with pytest.raises(ConfigError, match=r"no game pad number 0 \(found 0\); devices present: .*event0"):
        ev.find_device(None, 0, tmp_path)
    with pytest.raises(ConfigError, match=r"no input device at /dev/input/event99; devices present"):
        ev.find_device("/dev/input/event99", 0, tmp_path)
    with pytest.raises(ConfigError, match=r"no input devices present \(.*missing does not exist\)"):
        ev.find_device(None, 0, tmp_path / "missing")
