"""The Python frontend: a `.launch.py` file's `generate_launch_description()` → a LaunchDescription.

Launch files may import from `diffctl.launch`, or from `launch`, `launch_ros`, `launch_xml` and
`ament_index_python` as written for ROS 2: while a file loads, those module names are aliases of
`diffctl.launch` (events modules: of `diffctl.launch.events`). A name diffctl lacks fails with one line
naming it, never an AttributeError. Anything the file raises becomes one LaunchError naming file and line.
"""

from __future__ import annotations

import contextlib
import importlib.util
import inspect
import itertools
import re
import sys
import traceback
import types
from collections.abc import Iterator
from pathlib import Path

from diffctl.errors import DiffctlError, LaunchError, suggest
from diffctl.launch.context import Scope

ROS_MODULES = (
    "launch",
    "launch.actions",
    "launch.substitutions",
    "launch.conditions",
    "launch.event_handlers",
    "launch.events",
    "launch.events.process",
    "launch.launch_description_sources",
    "launch_xml",
    "launch_xml.launch_description_sources",
    "launch_yaml",
    "launch_yaml.launch_description_sources",
    "launch_ros",
    "launch_ros.actions",
    "launch_ros.substitutions",
    "launch_ros.parameter_descriptions",
    "launch_ros.descriptions",
    "launch_ros.event_handlers",
    "ament_index_python",
    "ament_index_python.packages",
)
EVENT_MODULES = ("launch.events", "launch.events.process")

_counter = itertools.count()


class MissingName(LaunchError, AttributeError):
    """A ROS launch name diffctl lacks: one line naming it; still an AttributeError, so `hasattr` feature checks
    in launch files see False instead of failing."""


class RosAliasModule(types.ModuleType):
    """A stand-in for a ROS launch module: what diffctl has, and a one-line error naming what it lacks."""

    def __getattr__(self, name: str) -> object:
        if name.startswith("__"):
            raise AttributeError(name)
        raise missing(self.__name__, name)


def missing(module: str, name: str) -> MissingName:
    # dir(), not vars(): diffctl.launch imports its names on first use and lists them all in __dir__.
    provided = sorted(k for k in dir(sys.modules.get(module, types.ModuleType(module))) if not k.startswith("_"))
    return MissingName(
        f"{module}.{name} is not supported by diffctl", hint=f"{module} here provides: " + ", ".join(provided)
    )


_CANNOT_IMPORT = re.compile(r"cannot import name '(\w+)' from '([\w.]+)'")


@contextlib.contextmanager
def ros_module_aliases() -> Iterator[None]:
    """`from launch.actions import …` / `from launch_ros.actions import Node` resolve to diffctl.launch."""
    import diffctl.launch as api
    from diffctl.launch import events

    saved = {name: sys.modules.get(name) for name in ROS_MODULES}
    try:
        modules: dict[str, types.ModuleType] = {}
        event_names = [
            k for k in vars(events) if (not k.startswith("_") and k[0].isupper()) or k.startswith("matches_")
        ]
        for name in ROS_MODULES:
            module = RosAliasModule(name, f"alias of diffctl.launch for ROS 2 launch files ({name})")
            if name in EVENT_MODULES:
                module.__dict__.update({k: getattr(events, k) for k in event_names})
            else:
                module.__dict__.update({k: getattr(api, k) for k in api.__all__})
                module.__dict__["LaunchContext"] = Scope
            module.__path__ = []  # a package, so submodule imports work
            modules[name] = module
            sys.modules[name] = module
        for name, module in modules.items():
            parent, _, child = name.rpartition(".")
            if parent:
                setattr(modules[parent], child, module)
        yield
    finally:
        for name, module in saved.items():
            if module is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = module


def _line_in(path: str, tb: types.TracebackType | None) -> int | None:
    line = None
    for frame, lineno in traceback.walk_tb(tb):
        if frame.f_code.co_filename == path:
            line = lineno
    return line


def _unexpected_keyword(error: TypeError) -> str:
    """`Node(packge=…)` → "Node() has no argument 'packge' (did you mean 'package'?)"."""
    m = re.search(r"__init__\(\) got an unexpected keyword argument '(\w+)'", str(error))
    cls = None
    for frame, _ in traceback.walk_tb(error.__traceback__):
        if frame.f_code.co_name == "__init__" and "self" in frame.f_locals:
            cls = type(frame.f_locals["self"])
            break
    if not m or cls is None:
        return str(error)
    known: list[str] = []
    for klass in inspect.getmro(cls):
        if "__init__" in klass.__dict__ and klass is not object:
            known += [p for p in inspect.signature(klass.__init__).parameters if p not in ("self", "kw", "kwargs")]
    return f"{cls.__name__}() has no argument {m.group(1)!r}{suggest(m.group(1), known)}"


def load(path: str | Path) -> object:
    from diffctl.launch.actions import LaunchDescription

    source = str(Path(path).resolve())
    if not Path(source).is_file():
        raise LaunchError("launch file does not exist", source=str(path))
    spec = importlib.util.spec_from_file_location(f"_diffctl_launch_file_{next(_counter)}", source)
    if spec is None or spec.loader is None:
        raise LaunchError("cannot load as Python", source=str(path))
    module = importlib.util.module_from_spec(spec)
    with ros_module_aliases():
        try:
            spec.loader.exec_module(module)
            generate = getattr(module, "generate_launch_description", None)
            if generate is None:
                raise LaunchError("defines no generate_launch_description()", source=str(path))
            description = generate()
        except SyntaxError as e:
            raise LaunchError(f"syntax error: {e.msg}", source=str(path), line=e.lineno, column=e.offset) from None
        except DiffctlError as e:
            if e.source is None:
                e.source, e.line = str(path), _line_in(source, e.__traceback__)
            raise
        except TypeError as e:
            line = _line_in(source, e.__traceback__)
            raise LaunchError(_unexpected_keyword(e), source=str(path), line=line) from None
        except ImportError as e:
            # `from launch.actions import X`: Python turns the module's MissingName into "cannot import name".
            m = _CANNOT_IMPORT.search(str(e))
            line = _line_in(source, e.__traceback__)
            if m and m.group(2) in ROS_MODULES:
                err = missing(m.group(2), m.group(1))
                err.source, err.line = str(path), line
                raise err from None
            raise LaunchError(f"launch file raised ImportError: {e}", source=str(path), line=line) from None
        except Exception as e:
            raise LaunchError(
                f"launch file raised {type(e).__name__}: {e}", source=str(path), line=_line_in(source, e.__traceback__)
            ) from None
    if not isinstance(description, LaunchDescription):
        raise LaunchError(
            f"generate_launch_description() returned {type(description).__name__}, not a LaunchDescription",
            source=str(path),
        )
    return description
