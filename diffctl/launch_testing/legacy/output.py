"""The pre-Dashing output checks of launch_testing.legacy: filters and expectations on raw (bytes) output."""

from __future__ import annotations

import io
import os
import re
from collections.abc import Callable
from typing import Any


def get_default_filtered_prefixes() -> list[bytes]:
    return [b"pid", b"rc"]


def get_default_filtered_patterns() -> list[bytes]:
    return []


def get_rmw_output_filter(rmw_implementation: str, filter_type: str) -> list[bytes]:
    """The lines an rmw is known to print (its `rmw_output_<filter_type>` resource in the ament index)."""
    import ament_index_python

    if filter_type not in ("prefixes", "patterns"):
        raise TypeError(f'Unsupported filter_type "{filter_type}". Supported types: [\'prefixes\', \'patterns\']')
    resource = "rmw_output_" + filter_type
    if not ament_index_python.has_resource(resource, rmw_implementation):
        return []
    content, _ = ament_index_python.get_resource(resource, rmw_implementation)
    return [line.encode() for line in content.splitlines()]


def create_output_lines_filter(filtered_prefixes: list[bytes] | None = None,
                               filtered_patterns: list[bytes] | None = None,
                               filtered_rmw_implementation: str | None = None) -> Callable[[bytes], bytes]:
    """A filter of bytes output dropping the lines that start with a prefix or match a pattern (plus what
    the rmw prints, when one is named)."""
    prefixes = list(filtered_prefixes or get_default_filtered_prefixes())
    patterns = list(filtered_patterns or get_default_filtered_patterns())
    if filtered_rmw_implementation:
        prefixes += get_rmw_output_filter(filtered_rmw_implementation, "prefixes")
        patterns += get_rmw_output_filter(filtered_rmw_implementation, "patterns")
    compiled = [re.compile(p) for p in patterns]
    separator = os.linesep.encode("ascii")

    def _filter(output: bytes) -> bytes:
        kept = [line for line in output.splitlines()
                if not any(line.startswith(p) for p in prefixes) and not any(c.match(line) for c in compiled)]
        if output.endswith(separator):
            kept.append(separator)
        return separator.join(kept)

    return _filter


OutputTest = tuple[io.BytesIO, Callable[[io.BytesIO, bytes], io.BytesIO], Callable[[io.BytesIO, Any], bool], list]


def create_output_lines_test(expected_lines: list[bytes]) -> OutputTest:
    """An output test passing once each expected line is contained in some line of the output."""

    def collate(output: io.BytesIO, addendum: bytes) -> io.BytesIO:
        output.write(addendum)
        return output

    def matched(output: io.BytesIO, expected: bytes) -> bool:
        return any(expected in line for line in output.getvalue().splitlines())

    return io.BytesIO(), collate, matched, expected_lines


def create_output_regex_test(expected_patterns: list[Any]) -> OutputTest:
    """An output test passing once each pattern is found in the output (its lines joined by '\\n')."""

    def collate(output: io.BytesIO, addendum: bytes) -> io.BytesIO:
        output.write(b"\n".join(addendum.splitlines()))
        return output

    def matched(output: io.BytesIO, pattern: Any) -> bool:
        return pattern.search(output.getvalue()) is not None

    return io.BytesIO(), collate, matched, expected_patterns


def create_output_test_from_file(output_file: str) -> OutputTest:
    """The output test of `output_file.txt` (lines) or else `output_file.regex` (one pattern a line)."""
    if os.path.isfile(output_file + ".txt"):
        with open(output_file + ".txt", "rb") as f:
            return create_output_lines_test(f.read().splitlines())
    if os.path.isfile(output_file + ".regex"):
        with open(output_file + ".regex", "rb") as f:
            return create_output_regex_test([re.compile(p) for p in f.read().splitlines()])
    raise RuntimeError(f"could not find output check file: {output_file}")
