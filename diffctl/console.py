"""The one place that imports rich: consoles, tables, coloured one-line messages.

Objects render themselves by implementing `__rich__` and building tables with `table()` here, so no
other module imports rich. Tests pass a string buffer to `make_console` and read what was printed.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterable, Sequence
from typing import IO, Any

from rich.console import Console
from rich.markup import escape
from rich.table import Table
from rich.text import Text

__all__ = ["Text", "console", "err_console", "error", "escape", "info", "make_console", "table", "warn"]

# Stable, readable colours for per-process prefixes in the launcher.
PREFIX_COLOURS = ("cyan", "green", "magenta", "yellow", "blue", "bright_cyan", "bright_green", "bright_magenta")


def make_console(file: IO[str] | None = None, *, no_color: bool = False, width: int | None = None) -> Console:
    """A rich console; `file=io.StringIO()` for tests, `no_color` honours --no-color and NO_COLOR."""
    no_color = no_color or "NO_COLOR" in os.environ
    stream = file if file is not None else sys.stdout
    if width is None and not (hasattr(stream, "isatty") and stream.isatty()):
        # Piped or captured output: rich would wrap tables at 80 columns and fold names; keep rows whole.
        width = int(os.environ.get("COLUMNS", "160"))
    return Console(
        file=file,
        no_color=no_color,
        highlight=False,
        soft_wrap=True,
        width=width,
        force_terminal=None if file is None else False,
    )


class _CurrentStream:
    """sys.stdout or sys.stderr as it is when written to, not as it was at import: a module that redirects the
    stream later (contextlib.redirect_stderr, pytest's capsys, a daemon reopening its log) gets diffctl's messages."""

    def __init__(self, name: str) -> None:
        self._name = name

    def _stream(self) -> IO[str]:
        return getattr(sys, self._name) or getattr(sys, f"__{self._name}__")

    def write(self, text: str) -> int:
        return self._stream().write(text)

    def flush(self) -> None:
        self._stream().flush()

    def isatty(self) -> bool:
        return self._stream().isatty()

    def fileno(self) -> int:
        return self._stream().fileno()

    @property
    def encoding(self) -> str:
        return getattr(self._stream(), "encoding", None) or "utf-8"


console = make_console(_CurrentStream("stdout"))  # type: ignore[arg-type]
err_console = make_console(_CurrentStream("stderr"))  # type: ignore[arg-type]


def table(title: str | None, columns: Sequence[str], rows: Iterable[Sequence[Any]], **kw: Any) -> Table:
    """A table renderable with the given column headers and rows (cells are str()'d)."""
    t = Table(title=title, title_justify="left", **kw)
    for c in columns:
        t.add_column(c)
    for r in rows:
        t.add_row(*[c if isinstance(c, Text) else escape(str(c)) for c in r])
    return t


def error(message: str, out: Console | None = None) -> None:
    (out or err_console).print(Text("error: ", style="bold red") + Text(message))


def warn(message: str, out: Console | None = None) -> None:
    (out or err_console).print(Text("warning: ", style="yellow") + Text(message))


def info(message: str, out: Console | None = None) -> None:
    (out or err_console).print(Text(message, style="dim"))
