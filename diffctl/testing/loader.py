"""A launch test file made ready to run: imported under its package's name, its TestRuns loaded and
validated, every problem one LaunchTestError naming the file and line (exit code 2, as launch_test's)."""

from __future__ import annotations

import importlib.util
import re
import sys
import unittest
from pathlib import Path
from typing import Any

from diffctl.errors import DiffctlError

ROS_MODULES = ("launch", "launch_ros", "launch_testing", "launch_testing_ros", "launch_pytest")


class LaunchTestError(DiffctlError):
    """A launch test file that cannot run: it does not import, its description cannot be made, a bad argument."""

    exit_code = 2


def module_name_for(path: Path) -> str:
    """The name a test file is imported under when no package is given: its file name without `.py`, made an
    identifier (`test_x.launch.py` → `test_x_launch`)."""
    stem = path.name[:-3] if path.name.endswith(".py") else path.name
    return re.sub(r"\W", "_", stem)


def forget_folders_taken_for_modules() -> None:
    """A folder named `launch/` (a package's launch files, the repository's) imported as a namespace package
    would hide the overlay's `launch`: such imports are dropped so the real module is found next time."""
    for name in ROS_MODULES:
        module = sys.modules.get(name)
        if module is not None and getattr(module, "__file__", None) is None:
            for key in [k for k in sys.modules if k == name or k.startswith(name + ".")]:
                del sys.modules[key]


def located(error: BaseException, path: Path) -> LaunchTestError:
    """`error`, raised by the test file's code, as one line naming the file and line it comes from."""
    from diffctl.launch_testing.launch_test import where_in

    return LaunchTestError(where_in(error, str(path)))


def load(path: Path, package_name: str | None = None) -> tuple[Any, list[Any]]:
    """The imported module and its validated TestRuns (named `<package>.<file>.launch_tests`)."""
    from diffctl.launch_testing.loader import LoadTestsFromPythonModule
    from diffctl.launch_testing.test_runner import LaunchTestRunner

    basename = path.name[:-3] if path.name.endswith(".py") else path.name
    package_name = package_name or basename
    forget_folders_taken_for_modules()
    try:
        spec = importlib.util.spec_from_file_location(package_name, path)
        if spec is None or spec.loader is None:
            raise LaunchTestError(f"{path}: not a Python file")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
    except LaunchTestError:
        raise
    except Exception as e:
        raise located(e, path) from None
    if not hasattr(module, "generate_test_description"):
        raise LaunchTestError(f"{path}: no generate_test_description() in this file",
                              hint="a launch test defines it; a launch_pytest file runs under pytest")
    try:
        runs = LoadTestsFromPythonModule(module, name=f"{package_name}.{basename}.launch_tests")
        LaunchTestRunner(runs).validate()
    except Exception as e:
        raise located(e, path) from None
    return module, runs


def describe(path: Path, runs: list[Any]) -> list[Any]:
    """Each run's launch description, made without launching it (what --show-args reads): the errors of
    generate_test_description, and a missing ReadyToTest, as LaunchTestErrors."""
    descriptions = []
    for run in runs:
        try:
            descriptions.append(run.get_launch_description())
        except unittest.SkipTest:
            continue
        except Exception as e:
            raise located(e, path) from None
    return descriptions
