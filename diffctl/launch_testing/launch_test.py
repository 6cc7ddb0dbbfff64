"""`launch_test FILE [name:=value …]`: run a launch test file (python -m launch_testing.launch_test).

Exit code 0 when every run passed, 1 on a failed test, 2 on a file that cannot run (it does not import, its
generate_test_description raises, a malformed argument): one line naming the file and line.
"""

from __future__ import annotations

import argparse
import importlib.util
import logging
import os
import sys
import traceback
from pathlib import Path
from typing import Any

from .junitxml import unittestResultsToXml
from .loader import LoadTestsFromPythonModule
from .print_arguments import print_arguments_of_launch_description
from .test_runner import LaunchTestRunner

_logger = logging.getLogger(__name__)


def _load_python_file_as_module(test_module_name: str, python_file_path: str) -> Any:
    spec = importlib.util.spec_from_file_location(test_module_name, python_file_path)
    if spec is None or spec.loader is None:
        raise RuntimeError(f"cannot load '{python_file_path}' as a Python module")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("launch_test_file", help="Path to the launch test.")
    parser.add_argument("--package-name", action="store", default=None,
                        help="Name of the package the test is in. Useful to aggregate xUnit reports.")
    parser.add_argument("-v", "--verbose", action="store_true", default=False, help="Run with verbose output")
    parser.add_argument("-s", "--show-args", "--show-arguments", action="store_true", default=False,
                        help="Show arguments that may be given to the launch test.")
    parser.add_argument("launch_arguments", nargs="*",
                        help="Arguments in '<name>:=<value>' format (for duplicates, last one wins).")
    parser.add_argument("--junit-xml", action="store", dest="xmlpath", default=None,
                        help="Do write xUnit reports to specified path.")


def parse_arguments() -> tuple[argparse.ArgumentParser, argparse.Namespace]:
    parser = argparse.ArgumentParser(description="Launch integration testing tool.")
    add_arguments(parser)
    return parser, parser.parse_args()


def run(parser: argparse.ArgumentParser, args: argparse.Namespace,
        test_runner_cls: type = LaunchTestRunner) -> int | None:
    """Load, validate and run the test file `args` names; 0 or 1 as the results are, None after --show-args."""
    if not os.path.isfile(args.launch_test_file):
        parser.error(f"Test file '{args.launch_test_file}' does not exist")
    args.launch_test_file = os.path.abspath(args.launch_test_file)
    basename = os.path.splitext(os.path.basename(args.launch_test_file))[0]
    if not args.package_name:
        args.package_name = basename
    module = _load_python_file_as_module(args.package_name, args.launch_test_file)
    test_runs = LoadTestsFromPythonModule(module, name=f"{args.package_name}.{basename}.launch_tests")
    runner = test_runner_cls(test_runs=test_runs, launch_file_arguments=args.launch_arguments, debug=args.verbose)
    runner.validate()
    if args.show_args:
        print_arguments_of_launch_description(launch_description=test_runs[0].get_launch_description())
        return None
    results = runner.run()
    if args.xmlpath:
        report = unittestResultsToXml(test_results=results, name=f"{args.package_name}.{basename}")
        report.write(args.xmlpath, encoding="utf-8", xml_declaration=True)
    return 0 if all(r.wasSuccessful() for r in results.values()) else 1


def where_in(error: BaseException, path: str) -> str:
    """`error` as one line, prefixed with the place in `path` it comes from (a syntax error's own line, else
    the deepest frame of the traceback inside that file, else the file alone)."""
    text = f"{type(error).__name__}: {error}"
    if isinstance(error, SyntaxError) and error.filename:
        return f"{error.filename}:{error.lineno}: {type(error).__name__}: {error.msg}"
    target = str(Path(path).resolve())
    line = None
    for frame, lineno in traceback.walk_tb(error.__traceback__):
        if str(Path(frame.f_code.co_filename).resolve()) == target:
            line = lineno
    text = " ".join(text.split())  # one line, whatever the exception's message holds
    return f"{path}:{line}: {text}" if line is not None else f"{path}: {text}"


def main() -> None:
    logging.basicConfig()
    parser, args = parse_arguments()
    if args.verbose:
        _logger.setLevel(logging.DEBUG)
    try:
        sys.exit(run(parser, args))
    except Exception as e:
        parser.error(where_in(e, args.launch_test_file))


if __name__ == "__main__":
    main()
