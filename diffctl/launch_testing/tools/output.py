"""Output helpers for tests: line filters, expected output read from files, and matching output."""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Iterable
from typing import Any

from .text import build_line_match, build_text_match

_ANSI_ESCAPE = re.compile(r"\x1b\[[0-?]*[ -/]*[@-~]")


def remove_ansi_escape_sequences(text: str) -> str:
    """`text` without terminal colour and cursor sequences."""
    return _ANSI_ESCAPE.sub("", text)


def get_default_filtered_prefixes() -> list[str]:
    """Lines a filter drops unless told otherwise: launch's own 'pid …' and 'rc …' lines."""
    return ["pid", "rc"]


def get_default_filtered_patterns() -> list[str]:
    return []


def basic_output_filter(filtered_prefixes: Iterable[str] | None = None,
                        filtered_patterns: Iterable[str] | None = None) -> Callable[[str], str]:
    """A function dropping every output line that starts with one of `filtered_prefixes` or matches (from its
    start) one of the regular expressions `filtered_patterns`; the other lines keep their line ends."""
    prefixes = tuple(get_default_filtered_prefixes() if filtered_prefixes is None else filtered_prefixes)
    patterns = [re.compile(p) for p in (get_default_filtered_patterns() if filtered_patterns is None
                                        else filtered_patterns)]

    def keep(line: str) -> bool:
        return not line.startswith(prefixes) and not any(p.match(line) for p in patterns)

    def _filter(output: str) -> str:
        return "".join(line for line in output.splitlines(keepends=True) if keep(line))

    return _filter


def expected_output_from_file(path: str, encoding: str | None = None) -> Any:
    """The expected output kept beside a test: `path.txt` (its lines, literally) or else `path.regex` (one
    regular expression per line)."""
    for suffix in (".txt", ".regex"):
        name = path + suffix
        if os.path.isfile(name):
            with open(name, encoding=encoding) as f:
                lines = f.read().splitlines()
            return lines if suffix == ".txt" else [re.compile(line) for line in lines]
    raise RuntimeError(f"could not find output check file: {path}")


def expect_output(text: str | None = None, *, lines: list[str] | None = None, expected_text: Any = None,
                  expected_lines: Any = None, strip_ansi_escape_sequences: bool = True,
                  strict: bool = False) -> bool:
    """Whether the output (`text` or `lines`, one of them) holds the expectation (`expected_text` or
    `expected_lines`, one of them; see tools.text). Text given where lines are expected is split, and lines
    given where text is expected are joined with '\\n'."""
    if (text is None) == (lines is None):
        raise ValueError("Either lines or text, but not both, must be specified")
    if (expected_text is None) == (expected_lines is None):
        raise ValueError("Either expected lines or text, but not both, must be specified")
    if expected_text is not None:
        actual = text if text is not None else "\n".join(lines or [])
        if strip_ansi_escape_sequences:
            actual = remove_ansi_escape_sequences(actual)
        return build_text_match(expected_text, strict=strict)(actual) is not None
    actual_lines = lines if lines is not None else (text or "").splitlines()
    if strip_ansi_escape_sequences:
        actual_lines = [remove_ansi_escape_sequences(line) for line in actual_lines]
    return build_line_match(expected_lines, strict=strict)(actual_lines) is not None


__all__ = [
    "basic_output_filter",
    "expect_output",
    "expected_output_from_file",
    "get_default_filtered_patterns",
    "get_default_filtered_prefixes",
]
