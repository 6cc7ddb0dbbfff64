"""`name:=value` launch arguments of the command line, as launch_test reads them."""

from __future__ import annotations


def parse_launch_arguments(launch_arguments: list[str]) -> list[tuple[str, str]]:
    """(name, value) pairs, in order of first appearance; a name given twice keeps its last value."""
    parsed: dict[str, str] = {}
    for argument in launch_arguments:
        name, separator, value = argument.partition(":=")
        if not separator or not name or (not value and argument.count(":=") == 1):
            raise RuntimeError(f"malformed launch argument '{argument}', expected format '<name>:=<value>'")
        parsed[name] = value
    return list(parsed.items())
