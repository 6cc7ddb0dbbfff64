"""Output filters for ROS launch tests: launch_testing's, plus the lines an rmw implementation prints
(its `rmw_output_prefixes` / `rmw_output_patterns` resources in the ament index; diffctl's bus prints none)."""

from __future__ import annotations

from collections.abc import Callable


def get_rmw_output_filter(rmw_implementation: str, filter_type: str) -> list[str]:
    """The prefixes or patterns (`filter_type`) of the lines `rmw_implementation` prints, one per line of
    its resource; none when it registered none."""
    import ament_index_python

    if filter_type not in ("prefixes", "patterns"):
        raise TypeError(f'Unsupported filter_type "{filter_type}". Supported types: [\'prefixes\', \'patterns\']')
    resource = "rmw_output_" + filter_type
    if not ament_index_python.has_resource(resource, rmw_implementation):
        return []
    content, _ = ament_index_python.get_resource(resource, rmw_implementation)
    return content.splitlines()


def basic_output_filter(filtered_prefixes: list[str] | None = None, filtered_patterns: list[str] | None = None,
                        filtered_rmw_implementation: str | None = None) -> Callable[[str], str]:
    """launch_testing's basic_output_filter, also dropping what `filtered_rmw_implementation` prints."""
    from diffctl.launch_testing.tools.output import (
        basic_output_filter as launch_filter,
    )
    from diffctl.launch_testing.tools.output import (
        get_default_filtered_patterns,
        get_default_filtered_prefixes,
    )

    prefixes = get_default_filtered_prefixes() if filtered_prefixes is None else list(filtered_prefixes)
    patterns = get_default_filtered_patterns() if filtered_patterns is None else list(filtered_patterns)
    if filtered_rmw_implementation:
        prefixes += get_rmw_output_filter(filtered_rmw_implementation, "prefixes")
        patterns += get_rmw_output_filter(filtered_rmw_implementation, "patterns")
    return launch_filter(prefixes, patterns)
