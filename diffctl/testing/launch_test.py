"""`launch_test FILE [name:=value …]`: run one launch test file as ROS's launch_test does.

`python -m diffctl.testing.launch_test` (and `diffctl test` for each file it runs). Exit code 0 when every run
passed, 1 on any failure, 2 when the file cannot be run (import error, no generate_test_description).
"""

from __future__ import annotations

import argparse
import os
import sys
import traceback
from pathlib import Path
from typing import Any

from diffctl.errors import DiffctlError


def parse_launch_arguments(items: list[str], parser: argparse.ArgumentParser) -> dict[str, str]:
    out: dict[str, str] = {}
    for item in items:
        name, sep, value = item.partition(":=")
        if not sep or not name:
            parser.error(f"malformed launch argument '{item}', expected format '<name>:=<value>'")
        out[name] = value
    return out


def make_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="launch_test", description="Run a launch test file.")
    parser.add_argument("launch_test_file", help="the launch test file (defines generate_test_description)")
    parser.add_argument("launch_arguments", nargs="*", help="name:=value arguments for the launch description")
    parser.add_argument("--package-name", default=None, help="the name test ids start with")
    parser.add_argument("--junit-xml", default=None, help="write JUnit XML results here")
    parser.add_argument("--log-dir", default=None, help="keep the processes' logs here")
    parser.add_argument("--artifacts", default=None, help="on failure: logs, a bag and a picture of the scene here")
    parser.add_argument("--no-isolation", action="store_true", help="use the bus of the environment as it is")
    parser.add_argument("--fork-server", action="store_true",
                        help="fork diffctl's components from a zygote (saves CPU when tests run side by side)")
    parser.add_argument("-s", "--show-args", action="store_true", help="show the launch arguments and exit")
    parser.add_argument("-v", "--verbose", action="store_true")
    return parser


def _show_args(path: Path, package_name: str | None) -> None:
    from diffctl.testing.loader import import_test_module, load_test_runs

    module = import_test_module(path, package_name)
    run = load_test_runs(module)[0]
    description, _ = run.description(lambda: None)
    print_arguments_of_launch_description(launch_description=description, source=str(path))


def print_arguments_of_launch_description(*, launch_description: Any, source: str = "<launch description>") -> None:
    """The launch arguments a description declares, as `launch_test --show-args` prints them."""
    from diffctl.launch_legacy.resolver import declared_arguments

    print("Arguments (pass arguments as '<name>:=<value>'):")
    arguments = declared_arguments(launch_description, source)
    if not arguments:
        print("\n  No arguments.")
    for a in arguments:
        print(f"\n    '{a.name}':")
        print(f"        {a.description or 'no description given'}")
        if a.default is not None:
            print(f"        (default: '{a.default}')")


def main(argv: list[str] | None = None) -> int:
    parser = make_parser()
    args = parser.parse_args(argv)
    path = Path(args.launch_test_file)
    if not path.is_file():
        parser.error(f"Test file '{path}' does not exist")
    arguments = parse_launch_arguments(args.launch_arguments, parser)
    from diffctl.workspace import find_workspace, use_in_children

    use_in_children(find_workspace(explicit=None))
    if args.fork_server:
        from diffctl.cli.fork_preload import SPEC
        from diffctl.testing.service import use_fork_server

        use_fork_server(SPEC)
    try:
        if args.show_args:
            _show_args(path, args.package_name)
            return 0
        from diffctl.testing import junit
        from diffctl.testing.runner import run_file

        result = run_file(
            path,
            arguments,
            package_name=args.package_name,
            log_dir=Path(args.log_dir) if args.log_dir else None,
            isolate=not args.no_isolation,
            artifacts=Path(args.artifacts) if args.artifacts else None,
        )
    except DiffctlError as e:
        print(f"launch_test: error: {e}", file=sys.stderr)
        return 2
    except Exception:
        traceback.print_exc()
        return 2
    if args.junit_xml:
        junit.write(result, Path(args.junit_xml))
    return 0 if result.ok else 1


def run_and_exit() -> None:
    """As a program: exit as soon as the results are out (every process of the launch is reaped by then, the
    router closed); the interpreter's own teardown of zenoh's and rclpy's threads would add a third of a second."""
    code = main()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


if __name__ == "__main__":
    run_and_exit()
