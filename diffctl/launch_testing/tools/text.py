"""Matching expected text or lines against process output: plain strings, regular expressions, or sequences
of either that must appear in order.

A matcher takes the actual text (or list of lines) and where to start, and answers the (start, end) span of
what it matched, or None. `strict` asks for the expectation to cover the output exactly from `start`.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Sequence
from typing import Any

Span = tuple[int, int]


def normalize_lineseps(lines: str) -> str:
    r"""`lines` with every line separator (the platform's, and a terminal's \r\n) made '\n'."""
    return lines.replace(os.linesep, "\n").replace("\r\n", "\n")


def _is_pattern(expected: Any) -> bool:
    return hasattr(expected, "match") and hasattr(expected, "search")


def _chain(parts: list[Callable[..., Span | None]], strict: bool) -> Callable[..., Span | None]:
    """Each part matched after the previous one's end; `strict`: with nothing left between them."""

    def match(actual: Any, start: int = 0) -> Span | None:
        first, end = start, start
        for index, part in enumerate(parts):
            found = part(actual, end)
            if found is None or found[0] < end or (strict and found[0] != end):
                return None
            if index == 0:
                first = found[0]
            end = found[1]
        return first, end

    return match


def build_line_match(expected_lines: Any, *, strict: bool = False) -> Callable[..., Span | None]:
    """A matcher of a list of lines: a string is found inside a line, a pattern must match a line from its
    beginning, a sequence of them in order on successive (`strict`) or later lines."""
    if isinstance(expected_lines, str):
        def has(line: str) -> bool:
            return expected_lines in line
        exact: Callable[[str], bool] = lambda line: line == expected_lines  # noqa: E731
    elif _is_pattern(expected_lines):
        def has(line: str) -> bool:
            return expected_lines.match(line) is not None
        exact = has
    elif isinstance(expected_lines, Iterable):
        return _chain([build_line_match(e) for e in expected_lines], strict)
    else:
        raise ValueError("Unknown format for expected lines")

    def match(actual_lines: Sequence[str], start: int = 0) -> Span | None:
        rest = actual_lines[start:]
        if strict:
            return (start, start + len(rest)) if all(exact(line) for line in rest) else None
        for index, line in enumerate(rest, start=start):
            if has(line):
                return index, index + 1
        return None

    return match


def build_text_match(expected_text: Any, *, strict: bool = False) -> Callable[..., Span | None]:
    """A matcher of a text: a string is found in it, a pattern searched (`strict`: matched where the search
    starts), a sequence of them found one after the other."""
    if isinstance(expected_text, str):
        def match(actual_text: str, start: int = 0) -> Span | None:
            text = normalize_lineseps(actual_text)
            if strict:
                return (start, start + len(expected_text)) if text[start:] == expected_text else None
            at = text.find(expected_text, start)
            return None if at < 0 else (at, at + len(expected_text))

        return match
    if _is_pattern(expected_text):
        def match(actual_text: str, start: int = 0) -> Span | None:
            text = normalize_lineseps(actual_text)
            found = (expected_text.match if strict else expected_text.search)(text, start)
            return None if found is None else (found.start(), found.end())

        return match
    if isinstance(expected_text, Iterable):
        chained = _chain([build_text_match(e) for e in expected_text], strict)
        return lambda actual_text, start=0: chained(normalize_lineseps(actual_text), start)
    raise ValueError("Unknown format for expected text")


__all__ = ["build_line_match", "build_text_match", "normalize_lineseps"]
