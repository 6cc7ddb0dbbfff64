"""`NAME:=VALUE` launch arguments as launch_testing's parse_arguments reads them (pairs, in order)."""

from __future__ import annotations

from diffctl.errors import ConfigError


def parse_launch_arguments(launch_arguments: list[str]) -> list[tuple[str, str]]:
    pairs = []
    for argument in launch_arguments:
        name, sep, value = argument.partition(":=")
        if not sep or not name:
            raise ConfigError(f"malformed launch argument {argument!r}, expected format '<name>:=<value>'")
        pairs.append((name, value))
    return pairs
