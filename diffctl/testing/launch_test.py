"""diffctl's `launch_test` command (console script; `diffctl test` runs it for each launch test file):
launch_testing's launch_test, with each run on a bus of its own, `--artifacts` for failed runs, and a file
that cannot run reported in one line naming its file and line.

Exit code 0 when every run passed, 1 on any failed test, 2 when the file cannot run.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from diffctl.errors import DiffctlError


def make_parser() -> argparse.ArgumentParser:
    from diffctl.launch_testing.launch_test import add_arguments

    parser = argparse.ArgumentParser(prog="launch_test", description="Launch integration testing tool.")
    add_arguments(parser)
    parser.add_argument("--log-dir", default=None, help="Write each process's output of each run here.")
    parser.add_argument("--artifacts", default=None,
                        help="On failure: each process's log, an MCAP bag of the run and a picture of the scene.")
    parser.add_argument("--no-isolation", action="store_true",
                        help="Use the bus of the environment as it is (default: a router and domain per run).")
    return parser


def _write_logs(result: object, folder: Path) -> None:
    runs = getattr(result, "runs", [])
    for index, record in enumerate(runs):
        where = folder / (f"run{index}" if len(runs) > 1 else "run")
        where.mkdir(parents=True, exist_ok=True)
        for name, text in record.logs.items():
            (where / name).write_text(text)


def run(argv: list[str] | None = None) -> int:
    parser = make_parser()
    args = parser.parse_args(argv)
    path = Path(args.launch_test_file)
    if not path.is_file():
        parser.error(f"Test file '{path}' does not exist")
    from diffctl.launch_testing.launch_test import where_in
    from diffctl.launch_testing.parse_arguments import parse_launch_arguments

    try:
        parse_launch_arguments(args.launch_arguments)
    except RuntimeError as e:
        parser.error(str(e))
    from diffctl.workspace import find_workspace, use_in_children

    use_in_children(find_workspace(explicit=None))
    try:
        if args.show_args:
            from diffctl.launch_testing.print_arguments import print_arguments_of_launch_description
            from diffctl.testing.loader import describe, load

            _, runs = load(path.resolve(), args.package_name)
            descriptions = describe(path, runs[:1])
            if not descriptions:  # its generate_test_description is skipped: nothing declared
                from diffctl.launch import LaunchDescription

                descriptions = [LaunchDescription()]
            print_arguments_of_launch_description(launch_description=descriptions[0])
            return 0
        from diffctl.testing import junit
        from diffctl.testing.runner import run_file

        result = run_file(path, args.launch_arguments, package_name=args.package_name,
                          isolate=not args.no_isolation, debug=args.verbose,
                          artifacts=Path(args.artifacts) if args.artifacts else None)
    except DiffctlError as e:
        print(f"launch_test: error: {e}", file=sys.stderr)
        return 2
    except Exception as e:  # raised by the file's own code while its runs were made
        print(f"launch_test: error: {where_in(e, str(path))}", file=sys.stderr)
        return 2
    if args.log_dir:
        _write_logs(result, Path(args.log_dir))
    if args.xmlpath:
        junit.write(result, Path(args.xmlpath))
    return 0 if result.ok else 1


def main(argv: list[str] | None = None) -> None:
    """As a program: exit as soon as the results are out (every process of the launch is reaped by then, the
    router closed); the interpreter's own teardown of zenoh's and rclpy's threads would add a third of a second."""
    code = run(argv)
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


if __name__ == "__main__":
    main()
