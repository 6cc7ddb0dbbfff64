"""pytest collects launch test files: a file whose generate_test_description is marked
`@pytest.mark.launch_test` becomes one item that runs all its TestRuns with LaunchTestRunner.

Only files whose text defines generate_test_description are imported at collection; every other file is left
to pytest untouched, and launch itself is imported only when such a file is collected (pytest loads this
plugin in every session).
"""

from __future__ import annotations

import copy
import pathlib
import re
from typing import Any
from unittest import TestCase

import pytest
from _pytest._code.code import ReprFileLocation

_DEFINES_ENTRYPOINT = re.compile(r"^\s*def\s+generate_test_description\s*\(", re.MULTILINE)


class LaunchTestFailure(Exception):
    """Some test cases of the launch test failed; `results` are the runs' results."""

    def __init__(self, message: str, results: dict[Any, Any]) -> None:
        super().__init__()
        self.message = message
        self.results = results

    def __str__(self) -> str:
        return self.message


class LaunchTestFailureRepr:
    """The report of a failed launch test item: each failed case's id and traceback, between rules."""

    def __init__(self, failures: list[tuple[str, str]]) -> None:
        lines = [line for _, text in failures for line in text.splitlines()]
        width = max((len(line) for line in lines), default=3)
        blocks = [f"{'=' * width}\nFAIL: {name}\n{'-' * width}\n{text}" for name, text in failures]
        self._fulldescr = "\n" + "\n\n".join(blocks)
        self.reprcrash = ReprFileLocation(path="", lineno=0,
                                          message="\n".join(f"{name} failed" for name, _ in failures))

    def __str__(self) -> str:
        return self._fulldescr

    def toterminal(self, out: Any) -> None:
        out.write(self._fulldescr)


class LaunchTestItem(pytest.Item):
    """All the runs of one launch test file, as one pytest test."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.test_runs: list[Any] | None = None
        self.runner_cls: type | None = None

    @classmethod
    def from_parent(cls, parent: Any, *, name: str, test_runs: list[Any],  # type: ignore[override]
                    runner_cls: type | None = None) -> LaunchTestItem:
        """`runner_cls` defaults to launch_testing.test_runner.LaunchTestRunner."""
        if runner_cls is None:
            from ..test_runner import LaunchTestRunner as runner_cls
        item = super().from_parent(parent, name=name)
        item.test_runs = test_runs
        item.runner_cls = runner_cls
        return item

    def runtest(self) -> None:
        arguments = [a for group in self.config.getoption("--launch-args") for a in group]
        # a copy per attempt: a rerun (pytest-rerunfailures) starts from unbound tests
        runner = self.runner_cls(test_runs=copy.deepcopy(self.test_runs), launch_file_arguments=arguments,
                                 debug=self.config.getoption("verbose"))
        runner.validate()
        results = runner.run()
        if not all(r.wasSuccessful() for r in results.values()):
            raise LaunchTestFailure(message="some test cases have failed", results=results)

    def repr_failure(self, excinfo: Any, style: Any = None) -> Any:
        if isinstance(excinfo.value, LaunchTestFailure):
            return LaunchTestFailureRepr([
                (case.id(), text)
                for result in excinfo.value.results.values() if not result.wasSuccessful()
                for case, text in result.errors + result.failures if isinstance(case, TestCase)
            ])
        return super().repr_failure(excinfo)

    def reportinfo(self) -> tuple[Any, int, str]:
        return self.path, 0, f"launch tests: {self.name}"


def _import(path: pathlib.Path) -> Any:
    """The test file as a module: as pytest imports it, but a file named like `test_x.launch.py` (a dotted
    name Python cannot import) under its name made an identifier (`test_x_launch`)."""
    if "." in path.name[:-3]:
        import importlib.util
        import sys

        name = re.sub(r"\W", "_", path.name[:-3])
        module = sys.modules.get(name)
        if module is not None and getattr(module, "__file__", None) == str(path):
            return module
        spec = importlib.util.spec_from_file_location(name, path)
        if spec is None or spec.loader is None:
            raise ImportError(f"cannot import {path}")
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
        return module
    from _pytest.pathlib import import_path

    try:
        return import_path(path, root=path.parent, consider_namespace_packages=False)
    except TypeError:  # pytest < 8.1
        return import_path(path, root=path.parent)


class LaunchTestModule(pytest.File):
    """A launch test file: it collects one LaunchTestItem named after the module."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        fspath = kwargs.pop("fspath", None)  # the py.path spelling of older plugins
        if fspath is not None and kwargs.get("path") is None:
            kwargs["path"] = pathlib.Path(str(fspath))
        super().__init__(*args, **kwargs)

    @classmethod
    def from_parent(cls, parent: Any, **kwargs: Any) -> Any:  # type: ignore[override]
        fspath = kwargs.pop("fspath", None)
        if fspath is not None and kwargs.get("path") is None:
            kwargs["path"] = pathlib.Path(str(fspath))
        return super().from_parent(parent, **kwargs)

    def makeitem(self, *args: Any, **kwargs: Any) -> Any:
        return LaunchTestItem.from_parent(*args, **kwargs)

    def collect(self) -> Any:
        from ..loader import LoadTestsFromPythonModule

        module = _import(self.path)
        yield self.makeitem(name=module.__name__, parent=self,
                            test_runs=LoadTestsFromPythonModule(module, name=module.__name__))


def find_launch_test_entrypoint(path: Any) -> Any:
    """The generate_test_description of the file at `path`, or None (none defined, or it does not compile)."""
    path = pathlib.Path(str(path))
    try:
        if not _DEFINES_ENTRYPOINT.search(path.read_text(errors="replace")):
            return None
        return getattr(_import(path), "generate_test_description", None)
    except (OSError, SyntaxError):
        return None


def pytest_pycollect_makemodule(module_path: Any, parent: Any) -> Any:
    entrypoint = find_launch_test_entrypoint(module_path)
    if entrypoint is None:
        return None
    ihook = parent.session.gethookproxy(module_path)
    return ihook.pytest_launch_collect_makemodule(path=pathlib.Path(module_path), parent=parent,
                                                  entrypoint=entrypoint)


@pytest.hookimpl(trylast=True)
def pytest_launch_collect_makemodule(path: Any, parent: Any, entrypoint: Any) -> Any:
    marks = getattr(entrypoint, "pytestmark", [])
    if not any(m.name == "launch_test" for m in marks):
        return None
    module = LaunchTestModule.from_parent(parent, path=pathlib.Path(str(path)))
    for mark in marks:  # the entrypoint's marks apply to the test (skip, xfail, …)
        module.add_marker(getattr(pytest.mark, mark.name).with_args(*mark.args, **mark.kwargs))
    return module


def pytest_addhooks(pluginmanager: Any) -> None:
    from . import hookspecs

    pluginmanager.add_hookspecs(hookspecs)


def pytest_addoption(parser: Any) -> None:
    parser.addoption("--launch-args", action="append", nargs="*", default=[],
                     help="One or more Launch test arguments")


def pytest_configure(config: Any) -> None:
    config.addinivalue_line(
        "markers", "launch_test: mark a generate_test_description function as a launch test entrypoint"
    )
