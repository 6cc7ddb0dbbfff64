"""xacro (the PyPI package, not a re-implementation) run in-process, with `$(find pkg)` through diffctl's index.

xacro resolves `$(find)` by importing ament_index_python lazily; here that lookup is swapped for diffctl's package
index for the duration of one run (xacro keeps module-global state, so runs are serialised). xacro's errors
carry no line numbers: the innermost file comes from its include stack, and the line is the first one of that
file holding the expression, argument or package the error names.
"""

from __future__ import annotations

import contextlib
import re
import threading
from collections.abc import Iterator
from pathlib import Path
from xml.parsers.expat import ExpatError

from diffctl.description.urdf.meshes import package_share
from diffctl.errors import DescriptionError, DiffctlError

XACRO_NAMESPACE = "http://www.ros.org/wiki/xacro"
_lock = threading.Lock()
_XACRO_TAG = re.compile(r"<xacro:|\$\{|\$\((?:arg|find|env|optenv|eval|dirname|cwd)\b")

# Phrases of xacro's messages that quote the text to look for in the file.
_LOCATORS = (
    (re.compile(r"when evaluating expression '(.+?)'", re.S), "{}"),
    (re.compile(r"Undefined substitution argument (\S+)"), "$(arg {})"),
    (re.compile(r"\$\(find (\S+?)\)"), "$(find {})"),
    (re.compile(r"unknown macro name: (?:xacro:)?(\S+)"), "{}"),
    (re.compile(r"[Ii]nvalid parameter \"?([\w.]+)"), "{}"),
    (re.compile(r"name '(\w+)' is not defined"), "{}"),
)


def _find(package: str) -> str:
    import xacro

    try:
        return str(package_share(package))
    except DiffctlError as e:
        raise xacro.XacroException(f"$(find {package}): {e.message}") from None


@contextlib.contextmanager
def _find_hook() -> Iterator[None]:
    from xacro import substitution_args

    saved = substitution_args._eval_find, substitution_args._eval_dict.get("find")
    substitution_args._eval_find = _find
    substitution_args._eval_dict["find"] = _find  # `$(eval find('pkg'))` reads the table, not the function
    try:
        yield
    finally:
        substitution_args._eval_find = saved[0]
        substitution_args._eval_dict["find"] = saved[1]


def _locate(file: str | None, message: str) -> int | None:
    if not file or not Path(file).is_file():
        return None
    try:
        lines = Path(file).read_text(errors="replace").splitlines()
    except OSError:
        return None
    for pattern, template in _LOCATORS:
        m = pattern.search(message)
        if m is None:
            continue
        needle = template.format(m.group(1).strip())
        for number, text in enumerate(lines, start=1):
            if needle in text:
                return number
    return None


def _error(e: Exception, top: str) -> DescriptionError:
    import xacro

    stack = [f for f in (xacro.filestack or []) if f]
    file = str(stack[-1]) if stack else top
    message = " ".join(str(e).split()) or repr(e)
    if isinstance(e, ExpatError):
        return DescriptionError(f"xacro: malformed XML: {message}", source=file, line=e.lineno, field="xacro")
    macros = [m for m in (xacro.macrostack or []) if getattr(m, "body", None)]
    hint = None
    if macros:
        # The failing text sits in the innermost macro's body, in the file that defined it.
        innermost = macros[-1]
        defined_in = innermost.history[-1][-1] if innermost.history and innermost.history[-1] else None
        hint = f"in macro {innermost.body.getAttribute('name')!r}, used in {file}"
        line = _locate(defined_in, message)
        if line is not None:
            return DescriptionError(f"xacro: {message}", source=str(defined_in), line=line, field="xacro", hint=hint)
    return DescriptionError(f"xacro: {message}", source=file, line=_locate(file, message), field="xacro", hint=hint)


def process_xacro(path: str | Path, mappings: dict[str, str] | None = None) -> str:
    """The URDF (or SDF) text a xacro file expands to, as the `xacro` command prints it."""
    import xacro

    p = Path(path)
    if not p.is_file():
        raise DescriptionError("no such file", source=str(p), hint="give the path of a .xacro or .urdf file")
    with _lock, _find_hook():
        try:
            doc = xacro.process_file(str(p), mappings=dict(mappings or {}))
        except Exception as e:  # xacro raises XacroException, ExpatError, NameError, … for bad input
            raise _error(e, str(p)) from None
    return doc.toprettyxml(indent="  ")


def process_xacro_text(text: str, base_dir: str | Path, source: str = "<string>") -> str:
    """xacro run on text (includes resolve against `base_dir`)."""
    import xacro

    with _lock, _find_hook():
        saved_root = xacro.root_dir
        xacro.root_dir = str(base_dir)
        try:
            xacro.init_stacks(None)
            doc = xacro.parse(text)
            xacro.process_doc(doc)
        except Exception as e:  # as above
            err = _error(e, source)
            if err.source in (None, "None", "string"):
                err.source = source
            raise err from None
        finally:
            xacro.root_dir = saved_root
    return doc.toprettyxml(indent="  ")


def uses_xacro(text: str) -> bool:
    """Whether text still holds xacro markup (expanded output keeps the namespace declaration, not the tags)."""
    return XACRO_NAMESPACE in text and _XACRO_TAG.search(text) is not None
