"""pytest plugin (entry point pytest11): launch test files run by pytest as launch_testing's plugin runs them.

Only files that define `generate_test_description()` marked `@pytest.mark.launch_test` (or `rostest`) are
taken, read as text first: every other file, diffctl's own tests included, is left to pytest untouched. Such a
file becomes one item, named after the module, that runs all its runs on a bus of their own; its failure lists
each failed test. Imports here stay light: pytest loads the plugin in every session.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

_LAUNCH_TEST = re.compile(r"^def generate_test_description\(", re.MULTILINE)
_MARKED = re.compile(r"mark\.(launch_test|rostest)\b")


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("launch_test", "launch tests (diffctl)")
    group.addoption("--launch-args", action="append", nargs="*", default=[],
                    help="name:=value arguments for launch test descriptions")


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line("markers", "launch_test: a launch test file's generate_test_description (launch_testing)")
    config.addinivalue_line("markers", "rostest: a ROS launch test file's generate_test_description")
    # ament_copyright is diffctl's own (diffctl/testing/copyright.py): its marker, as ament_copyright registers it
    config.addinivalue_line("markers", "copyright: marks tests checking for copyright notices")


def is_marked_launch_test(path: Path) -> bool:
    try:
        text = path.read_text(errors="replace")
    except OSError:
        return False
    return bool(_LAUNCH_TEST.search(text) and _MARKED.search(text))


def pytest_pycollect_makemodule(module_path: Path, parent: pytest.Collector) -> Any:
    if is_marked_launch_test(Path(module_path)):
        return LaunchTestModule.from_parent(parent, path=Path(module_path))
    return None


class LaunchTestFailure(Exception):
    def __init__(self, report: str) -> None:
        super().__init__(report)
        self.report = report


class LaunchTestItem(pytest.Item):
    def runtest(self) -> None:
        from diffctl.testing.launch_test import parse_launch_arguments
        from diffctl.testing.runner import run_file
        from diffctl.workspace import find_workspace, use_in_children

        raw = [a for group in self.config.getoption("launch_args") or [] for a in group]
        arguments = parse_launch_arguments(raw, _Fail())
        saved = dict(os.environ)
        try:
            use_in_children(find_workspace(start=self.path.parent))
            result = run_file(self.path, arguments, package_name=self.name)
        finally:
            os.environ.clear()
            os.environ.update(saved)
        if not result.ok:
            raise LaunchTestFailure(_report(result))

    def repr_failure(self, excinfo: pytest.ExceptionInfo[BaseException], style: Any = None) -> Any:
        if isinstance(excinfo.value, LaunchTestFailure):
            return excinfo.value.report
        return super().repr_failure(excinfo)

    def reportinfo(self) -> tuple[Path, int, str]:
        return self.path, 0, f"launch test: {self.name}"


class LaunchTestModule(pytest.File):
    def collect(self) -> Iterator[pytest.Item]:
        from diffctl.testing.loader import module_name_for

        yield LaunchTestItem.from_parent(self, name=module_name_for(self.path))


class _Fail:
    def error(self, message: str) -> None:
        raise pytest.UsageError(message)


def _report(result: Any) -> str:
    lines = []
    if result.error:
        lines.append(result.error)
    for one in result.runs:
        for r in one.results:
            for case, text in [*r.failures, *r.errors]:
                lines.append(f"FAIL: {case.id()}\n{text}")
    return "\n".join(lines) or "launch test failed"
