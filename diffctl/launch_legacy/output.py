"""Where process output and the launcher's messages go: the terminal, one log file per process, launch.log.

Every line a child prints is shown as `[name] line` with the name in a stable colour (the same name gets
the same colour in every run). While processes are starting, one live line at the bottom says which are
up and what is still awaited; it is cleared before any other line is printed and redrawn after it.
"""

from __future__ import annotations

import shutil
import sys
import time
import zlib
from pathlib import Path
from typing import IO, Any

from diffctl.console import PREFIX_COLOURS, Text, make_console
from diffctl.launch_legacy.commandline import file_stem

# rich answers a broken pipe with SystemExit(1); for the launcher a closed screen is no reason to stop.
_BROKEN_PIPE = (OSError, SystemExit)

LEVEL_STYLES = {"INFO": "", "WARN": "yellow", "ERROR": "bold red"}


def colour_of(name: str) -> str:
    return PREFIX_COLOURS[zlib.crc32(name.encode()) % len(PREFIX_COLOURS)]


class Output:
    def __init__(
        self,
        *,
        log_dir: Path | None = None,
        no_color: bool = False,
        stream: IO[str] | None = None,
        live: bool | None = None,
    ) -> None:
        target = stream if stream is not None else sys.stdout
        # file=None lets rich detect a terminal (colours); an explicit stream is a test or a pipe.
        self.console = make_console(stream, no_color=no_color)
        self.stream = target
        self.live_enabled = live if live is not None else bool(getattr(target, "isatty", lambda: False)())
        self._live: str | None = None
        self._screen_gone = False
        self.log_dir = log_dir
        self._files: dict[str, IO[str]] = {}
        self._launch_log: IO[str] | None = None
        if log_dir is not None:
            log_dir.mkdir(parents=True, exist_ok=True)
            self._launch_log = open(log_dir / "launch.log", "a", buffering=1, encoding="utf-8")  # noqa: SIM115

    # ---- lines -----------------------------------------------------------------------------------------------

    def process_line(self, name: str, stream: str, text: str, *, screen: bool) -> None:
        file = self._file(name)
        if file is not None:
            file.write(text + "\n")
        if screen:
            self._print(Text(f"[{name}] ", style=colour_of(name)) + Text(text))

    def launcher(self, level: str, message: str, logger: str = "launch") -> None:
        """A line of the launcher's own (`logger` as ROS names it: `launch`, or `launch.user` for LogInfo)."""
        if self._launch_log is not None:
            stamp = time.strftime("%H:%M:%S", time.localtime()) + f".{int(time.time() * 1000) % 1000:03d}"
            self._launch_log.write(f"{stamp} [{level}] {message}\n")
        self._print(Text(f"[{level}] [{logger}]: {message}", style=LEVEL_STYLES.get(level, "")))

    def show(self, renderable: Any) -> None:
        if self._screen_gone:
            return
        try:
            self._clear_live()
            self.console.print(renderable)
            self._draw_live()
        except _BROKEN_PIPE:
            self._screen_gone = True

    # ---- the live start-up line ------------------------------------------------------------------------------

    def live(self, text: str | None) -> None:
        if not self.live_enabled or text == self._live or self._screen_gone:
            return
        try:
            self._clear_live()
            self._live = text
            self._draw_live()
        except _BROKEN_PIPE:
            self._screen_gone = True

    def _clear_live(self) -> None:
        if self._live is not None:
            self.stream.write("\r\x1b[2K")
            self.stream.flush()

    def _draw_live(self) -> None:
        if self._live is not None:
            width = shutil.get_terminal_size((100, 20)).columns - 1
            text = self._live if len(self._live) <= width else self._live[: width - 1] + "…"
            self.stream.write(f"\x1b[2m{text}\x1b[0m")
            self.stream.flush()

    def _print(self, text: Text) -> None:
        if self._screen_gone:
            return
        try:
            self._clear_live()
            self.console.print(text)
            self._draw_live()
        except _BROKEN_PIPE:
            # `diffctl launch … | head` closed our stdout: keep supervising, logging to files only.
            self._screen_gone = True

    # ---- files -----------------------------------------------------------------------------------------------

    def _file(self, name: str) -> IO[str] | None:
        if self.log_dir is None:
            return None
        file = self._files.get(name)
        if file is None:
            file = open(self.log_dir / f"{file_stem(name)}.log", "a", buffering=1, encoding="utf-8")  # noqa: SIM115
            self._files[name] = file
        return file

    def close(self) -> None:
        self.live(None)
        self._live = None
        for file in self._files.values():
            file.close()
        self._files.clear()
        if self._launch_log is not None:
            self._launch_log.close()
            self._launch_log = None


def link_latest(log_dir: Path) -> None:
    """`latest` next to the run's directory points at it, as ros2 launch does."""
    latest = log_dir.parent / "latest"
    try:
        if latest.is_symlink() or latest.exists():
            latest.unlink()
        latest.symlink_to(log_dir.name)
    except OSError:
        pass
