"""The `ament_index` command (ament_index_python.cli): list resource types, a type's resources, or one
resource's prefix and content; with shell completers for both arguments."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from diffctl.workspace.resource_index import get_resource, get_resource_types, get_resources


def resource_type_completer(prefix: str, **kwargs: Any) -> list[str]:
    return [t for t in get_resource_types() if t.startswith(prefix)]


def resource_name_completer(prefix: str, parsed_args: Any, **kwargs: Any) -> list[str]:
    resource_type = getattr(parsed_args, "resource_type", None)
    if resource_type is None:
        return []
    return [name for name in get_resources(resource_type) if name.startswith(prefix)]


def main(argv: list[str] | None = None) -> str | None:
    """Print the query's answer; a resource that cannot be found or read comes back as the message (the
    console script exits with it)."""
    parser = argparse.ArgumentParser(description="Query the ament resource index.")
    kind = parser.add_argument("resource_type", nargs="?", metavar="TYPE", help="The type of the resource")
    kind.completer = resource_type_completer  # type: ignore[attr-defined]
    name = parser.add_argument("resource_name", nargs="?", metavar="NAME", help="The name of the resource")
    name.completer = resource_name_completer  # type: ignore[attr-defined]
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    lines: list[str]
    if args.resource_type is None:
        lines = sorted(get_resource_types())
    elif args.resource_name is None:
        lines = [f"{name}\t{where}" for name, where in sorted(get_resources(args.resource_type).items())]
    else:
        try:
            content, where = get_resource(args.resource_type, args.resource_name)
        except (LookupError, OSError) as e:
            return str(e)
        # the content is fenced only when the resource file holds something
        lines = [where, "<<<", content, ">>>"] if content else [where]
    for line in lines:
        print(line)
    return None
