"""The Python frontend: a `.launch.py` file's `generate_launch_description()` → a LaunchDescription.

Launch files may import from `diffctl.launch_legacy`, or from `launch`, `launch_ros`, `launch_xml` and
`ament_index_python` as written for ROS 2: those are the overlay's modules (diffctl/overlay, names mapped in
ros_names.py), real modules on sys.path, so functions the engine calls later (an OpaqueFunction, a handler)
import them too. A name diffctl lacks fails with one line naming it, never an AttributeError. Anything the
file raises becomes one LaunchError naming file and line.
"""

from __future__ import annotations

import importlib.util
import inspect
import itertools
import re
import sys
import traceback
import types
from pathlib import Path

from diffctl.errors import DiffctlError, LaunchError, suggest
from diffctl.launch_legacy.ros_names import missing

ROS_MODULES = ("launch", "launch_ros", "launch_xml", "launch_yaml", "ament_index_python")


def _is_ros_module(name: str) -> bool:
    return name.split(".")[0] in ROS_MODULES


_counter = itertools.count()
_CANNOT_IMPORT = re.compile(r"cannot import name '(\w+)' from '([\w.]+)'")


def use_overlay() -> None:
    """The overlay's `launch`, `launch_ros`, … first on this process's sys.path.

    This process is diffctl's launcher: the file it loads must build diffctl's entities, even where a sourced
    ROS 2 puts its own `launch` earlier on PYTHONPATH (the processes the launch starts still get the sourced
    ROS first: `diffctl.workspace.use_in_children`)."""
    from diffctl.workspace import PYTHON_PATH

    # The legacy engine's own `launch`, `launch_xml`, `launch_yaml`, `launch_ros` (ros_overlay/) come before the
    # overlay's, which are diffctl.launch*: this process runs the legacy engine, its launch files must build its
    # entities.
    legacy = str(Path(__file__).with_name("ros_overlay"))
    for folder in (str(PYTHON_PATH), legacy):
        if sys.path[:1] != [folder]:
            if folder in sys.path:
                sys.path.remove(folder)
            sys.path.insert(0, folder)
    for name, module in list(sys.modules.items()):
        if name.split(".")[0] in ("launch", "launch_xml", "launch_yaml", "launch_ros") and (
            getattr(module, "__name__", "").startswith("diffctl.launch")
            and not getattr(module, "__name__", "").startswith("diffctl.launch_legacy")
        ):
            del sys.modules[name]


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
    from diffctl.launch_legacy.actions import LaunchDescription

    source = str(Path(path).resolve())
    if not Path(source).is_file():
        raise LaunchError("launch file does not exist", source=str(path))
    spec = importlib.util.spec_from_file_location(f"_diffctl_launch_file_{next(_counter)}", source)
    if spec is None or spec.loader is None:
        raise LaunchError("cannot load as Python", source=str(path))
    module = importlib.util.module_from_spec(spec)
    use_overlay()
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
        if m and _is_ros_module(m.group(2)):
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
