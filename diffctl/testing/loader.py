"""Reading a launch test file: its `generate_test_description`, its parametrized runs and its TestCases.

As launch_testing's loader: the module is imported from its path under a name of the caller's choosing; each
run gets its own copies of the file's TestCase classes, split into tests that run while the launch does and
`post_shutdown_test` ones; test methods (and setUp/tearDown, setUpClass/tearDownClass) get the values they
name as arguments — the dict returned by generate_test_description, parametrize's values, and proc_output,
proc_info, test_args, launch_service.
"""

from __future__ import annotations

import functools
import importlib.util
import inspect
import re
import sys
import unittest
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from diffctl.errors import DiffctlError
from diffctl.launch_legacy.actions import Action, walk_entities
from diffctl.testing.decorators import ReadyToTest

DEFAULT_READY_TIMEOUT_S = 15.0


class LaunchTestError(DiffctlError):
    """A launch test file that cannot be run (exit code 2, as launch_test's)."""

    exit_code = 2


def module_name_for(path: Path) -> str:
    """The name a test file is imported under: its file name without `.py`, made an identifier
    (`test_x.launch.py` → `test_x_launch`)."""
    stem = path.name[:-3] if path.name.endswith(".py") else path.name
    return re.sub(r"\W", "_", stem)


ROS_MODULES = ("launch", "launch_ros", "launch_testing", "launch_testing_ros", "launch_pytest")


def forget_folders_taken_for_modules() -> None:
    """A folder named `launch/` (a package's launch files, the repository's) imported as a namespace package
    would hide the overlay's `launch`: such imports are dropped so the real module is found next time."""
    for name in ROS_MODULES:
        module = sys.modules.get(name)
        if module is not None and getattr(module, "__file__", None) is None:
            for key in [k for k in sys.modules if k == name or k.startswith(name + ".")]:
                del sys.modules[key]


def import_test_module(path: Path, name: str | None = None) -> Any:
    from diffctl.launch_legacy.python_frontend import use_overlay

    use_overlay()  # until launch_testing runs on diffctl.launch: the test's `launch` is the legacy engine's
    name = name or module_name_for(path)
    forget_folders_taken_for_modules()
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None or spec.loader is None:
        raise LaunchTestError(f"{path}: not a Python file")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    if not hasattr(module, "generate_test_description"):
        raise LaunchTestError(
            f"{path}: no generate_test_description() in this file", hint="a launch test defines it"
        )
    return module


def find_ready_action(description: Any) -> ReadyToTest | None:
    for entity in walk_entities(description):
        if isinstance(entity, ReadyToTest):
            return entity
    return None


class TestRun:
    """One launch of the test file and its tests (one per parametrize value)."""

    def __init__(self, name: str, description_fn: Callable[[], Any], param_args: dict[str, Any],
                 module: Any, markers: dict[str, Any], timeout_s: float) -> None:
        self.name = name
        self.description_fn = description_fn
        self.param_args = param_args
        self.markers = markers
        self.timeout_s = timeout_s
        self.pre_shutdown_tests = _load(module, post_shutdown=False)
        self.post_shutdown_tests = _load(module, post_shutdown=True)
        if param_args:
            for case in self.all_cases():
                method = getattr(case, case._testMethodName)
                renamed = case._testMethodName + self.format_params()
                case._testMethodName = renamed
                setattr(case, renamed, method)

    def format_params(self) -> str:
        return "[" + ", ".join(str(v) for v in self.param_args.values()) + "]" if self.param_args else ""

    def __str__(self) -> str:
        return self.name + self.format_params()

    def all_cases(self) -> Iterator[unittest.TestCase]:
        yield from iterate_cases(self.pre_shutdown_tests)
        yield from iterate_cases(self.post_shutdown_tests)

    def description(self, ready: Callable[[], None]) -> tuple[Any, dict[str, Any]]:
        """Call generate_test_description; the ReadyToTest found in it calls `ready`."""
        result = self.description_fn()
        description, context = result if isinstance(result, tuple) else (result, {})
        if not isinstance(description, Action):
            raise LaunchTestError(
                f"generate_test_description returned {type(description).__name__}, not a LaunchDescription"
            )
        action = find_ready_action(description)
        if action is None:
            raise LaunchTestError(
                "generate_test_description functions must return a LaunchDescription containing a ReadyToTest action"
            )
        action._add_callback(ready)
        return description, dict(context or {})

    def bind(self, suite: unittest.TestSuite, args: dict[str, Any], attributes: dict[str, Any]) -> None:
        for cls in iterate_classes(suite):
            for attr, value in attributes.items():
                setattr(cls, attr, value)
            cls.setUpClass = _bind(cls.setUpClass, args)
            cls.tearDownClass = _bind(cls.tearDownClass, args)
        for case in iterate_cases(suite):
            setattr(case, case._testMethodName, _bind(getattr(case, case._testMethodName), args))
            case.setUp = _bind(case.setUp, args)
            case.tearDown = _bind(case.tearDown, args)


def load_test_runs(module: Any, name: str = "launch_tests") -> list[TestRun]:
    fn = module.generate_test_description
    markers = dict(getattr(fn, "__markers__", {}))
    timeout_s = float(getattr(fn, "__ready_to_test_action_timeout__", DEFAULT_READY_TIMEOUT_S))
    if getattr(fn, "__parametrized__", False):
        runs = list(fn())
    else:
        params = [p for p in inspect.signature(fn).parameters.values() if p.default is inspect.Parameter.empty]
        if params:
            raise LaunchTestError(
                f"generate_test_description has unexpected extra argument '{params[0].name}'",
                hint="arguments come from @launch_testing.parametrize",
            )
        runs = [(fn, {})]
    out = []
    for description_fn, args in runs:
        run_timeout = float(getattr(description_fn, "__ready_to_test_action_timeout__", timeout_s))
        inner = getattr(description_fn, "func", None)
        if inner is not None:
            run_timeout = float(getattr(inner, "__ready_to_test_action_timeout__", run_timeout))
        out.append(TestRun(name, description_fn, args, module, markers, run_timeout))
    return out


def _load(module: Any, *, post_shutdown: bool) -> unittest.TestSuite:
    loader = unittest.TestLoader()
    suite = unittest.TestSuite()
    for value in list(vars(module).values()):
        if not (inspect.isclass(value) and issubclass(value, unittest.TestCase)):
            continue
        if getattr(value, "__module__", None) != module.__name__ and value is not unittest.TestCase:
            continue  # a TestCase imported from elsewhere is not this file's
        if bool(getattr(value, "__post_shutdown_test__", False)) != post_shutdown:
            continue
        # A copy of the class per run: what one run binds to it does not leak into the next.
        copy = type(value.__name__, (value,), {"__module__": value.__module__, "__qualname__": value.__qualname__})
        suite.addTests(loader.loadTestsFromTestCase(copy))
    _keep_cases(suite)
    return suite


class PreShutdownTestLoader(unittest.TestLoader):
    """unittest's loader keeping only the TestCase classes that run while the launch is up (launch_testing's)."""

    post_shutdown = False

    def loadTestsFromTestCase(self, testCaseClass: type) -> unittest.TestSuite:
        if bool(getattr(testCaseClass, "__post_shutdown_test__", False)) != self.post_shutdown:
            return self.suiteClass([])
        return super().loadTestsFromTestCase(testCaseClass)


class PostShutdownTestLoader(PreShutdownTestLoader):
    """unittest's loader keeping only the `@post_shutdown_test()` classes."""

    post_shutdown = True


def _keep_cases(suite: unittest.TestSuite) -> None:
    """A suite drops each case after running it; the cases (their names, their classes) are kept for reports."""
    suite._cleanup = False
    for test in suite:
        if isinstance(test, unittest.TestSuite):
            _keep_cases(test)


def _bind(function: Callable[..., Any], candidates: dict[str, Any]) -> Callable[..., Any]:
    try:
        parameters = inspect.signature(function).parameters
    except (TypeError, ValueError):
        return function
    matching = {k: v for k, v in candidates.items() if k in parameters}
    return functools.partial(function, **matching) if matching else function


def iterate_cases(suite: Any) -> Iterator[unittest.TestCase]:
    if isinstance(suite, unittest.TestSuite):
        for test in suite:
            yield from iterate_cases(test)
    else:
        yield suite


def iterate_classes(suite: Any) -> Iterator[type]:
    seen: list[type] = []
    for case in iterate_cases(suite):
        if type(case) not in seen:
            seen.append(type(case))
            yield type(case)
