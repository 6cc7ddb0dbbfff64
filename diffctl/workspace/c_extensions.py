"""Loading a package's compiled extension module (ROS's rpyutils): Windows needs the folders of the DLLs it
links against named before the import; elsewhere the loader finds them itself and nothing is added."""

from __future__ import annotations

import importlib
import os
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from types import ModuleType
from typing import Any


@contextmanager
def add_dll_directories_from_env(env_name: str) -> Iterator[list[Any]]:
    """While inside, every existing folder listed in the variable `env_name` is on Windows' DLL search path;
    yields the handles (none on other systems), which are closed on leaving."""
    handles: list[Any] = []
    add = getattr(os, "add_dll_directory", None)
    if sys.platform == "win32" and add is not None:
        for folder in (os.environ.get(env_name) or "").split(os.pathsep):
            if folder and os.path.isdir(folder):
                handles.append(add(os.path.abspath(folder)))
    try:
        yield handles
    finally:
        while handles:
            handles.pop().close()


def import_c_library(name: str, package: str | None = None) -> ModuleType:
    """`importlib.import_module(name, package)` with PATH's folders searched for DLLs; a failed import says
    whether the extension was missing or present but unloadable."""
    try:
        with add_dll_directories_from_env("PATH"):
            return importlib.import_module(name, package=package)
    except ImportError as e:
        if e.path is not None and os.path.isfile(e.path):
            e.msg += f"\nThe C extension '{e.path}' exists but could not be loaded (a library it links against?)"
        elif e.path is None:
            e.msg += f"\nNo C extension module {name!r} was found on sys.path (is its package built and installed?)"
        raise
