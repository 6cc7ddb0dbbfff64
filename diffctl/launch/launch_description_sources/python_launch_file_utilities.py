"""Python launch files: modules defining `generate_launch_description()`."""

from __future__ import annotations

import importlib.util
from importlib.machinery import SourceFileLoader
from types import ModuleType
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..launch_description import LaunchDescription

_MODULE_NAME = 'python_launch_file'  # the `__name__` a launch file sees, as in ROS 2


class InvalidPythonLaunchFileError(Exception):
    """A Python launch file lacks `generate_launch_description()`."""


def load_python_launch_file_as_module(python_launch_file_path: str) -> ModuleType:
    """Run a Python launch file as a fresh module and return it (any file name: the loader is explicit)."""
    loader = SourceFileLoader(_MODULE_NAME, python_launch_file_path)
    spec = importlib.util.spec_from_file_location(_MODULE_NAME, python_launch_file_path, loader=loader)
    if spec is None:
        raise RuntimeError('Failed to load module spec!')
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


def get_launch_description_from_python_launch_file(python_launch_file_path: str) -> LaunchDescription:
    """What the file's `generate_launch_description()` returns.

    A launch file may be loaded only to be described (`--show-args`): loading it should start nothing.
    """
    generate = getattr(load_python_launch_file_as_module(python_launch_file_path), 'generate_launch_description', None)
    if generate is None:
        raise InvalidPythonLaunchFileError(
            f"launch file at '{python_launch_file_path}' does not contain the required function "
            "'generate_launch_description()'")
    return generate()
