"""launch_testing_ros.tools' output filters: launch_testing's prefix/pattern filter plus what the rmw prints.

ROS reads an rmw's noise from the ament index (`rmw_output_prefixes` / `rmw_output_patterns` resources of
that rmw); diffctl's bus is the one rmw here, rmw_zenoh_cpp's wire, and prints nothing on a process's
output of its own: its lists are empty, for any rmw name given.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from diffctl.testing.tools import basic_output_filter as _launch_filter

RMW_OUTPUT: dict[str, tuple[list[str], list[str]]] = {"rmw_zenoh_cpp": ([], [])}


def get_rmw_output_filter(rmw_implementation: str, filter_type: str) -> list[str]:
    """The lines (`prefixes` or `patterns`) the rmw is known to print; empty for an rmw with none."""
    if filter_type not in ("prefixes", "patterns"):
        raise ValueError(f"filter_type must be 'prefixes' or 'patterns', got {filter_type!r}")
    prefixes, patterns = RMW_OUTPUT.get(rmw_implementation, ([], []))
    return list(prefixes if filter_type == "prefixes" else patterns)


def basic_output_filter(
    filtered_prefixes: Iterable[str] | None = None,
    filtered_patterns: Iterable[str] | None = None,
    filtered_rmw_implementation: str | None = None,
) -> Callable[[str], str]:
    prefixes = list(filtered_prefixes or [])
    patterns = list(filtered_patterns or [])
    if filtered_rmw_implementation:
        prefixes += get_rmw_output_filter(filtered_rmw_implementation, "prefixes")
        patterns += get_rmw_output_filter(filtered_rmw_implementation, "patterns")
    return _launch_filter(filtered_prefixes=prefixes, filtered_patterns=patterns)
