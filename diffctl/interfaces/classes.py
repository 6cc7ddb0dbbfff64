"""Interface modules built on import: packages, their msg/srv/action modules and one module per interface.

`<pkg>` is an empty package; `<pkg>.msg` (`.srv`, `.action`) exports what rosidl's `__init__` exports (the
message classes; services with their `_Request`, `_Response` and `_Event`; actions with their `_SendGoal_*`
and `_GetResult_*`), each built on first access from `<pkg>.<kind>._<snake>`, whose source
`pysource.py` writes. The source is registered with linecache, so tracebacks through a setter's assertion
show the line, as they do through rosidl's files; its bytecode is cached (`bytecode.py`).
"""

from __future__ import annotations

import importlib
import keyword
import linecache
import types
from typing import Any

from diffctl.interfaces import pysource, registry
from diffctl.interfaces.bytecode import compiled
from diffctl.interfaces.idl import InterfaceError, TypeDef
from diffctl.interfaces.registry import InterfacePackage

# class → its type name (pkg/msg/T, pkg/srv/T_Request, …): what the codecs and type_name() key on.
NAMES: dict[type, str] = {}
CLASSES: dict[str, type] = {}


class TypeSupport:
    """What `__import_type_support__()` records: diffctl needs no C type support, only the type's name."""

    __slots__ = ("typename",)

    def __init__(self, typename: str) -> None:
        self.typename = typename

    def __repr__(self) -> str:
        return f"<diffctl type support {self.typename}>"


def import_type_support(cls: type, typename: str) -> None:
    support = TypeSupport(typename)
    cls._TYPE_SUPPORT = support  # type: ignore[attr-defined]
    if "_CREATE_ROS_MESSAGE" in vars(cls):
        for attr in ("_CREATE_ROS_MESSAGE", "_CONVERT_FROM_PY", "_CONVERT_TO_PY", "_DESTROY_ROS_MESSAGE"):
            setattr(cls, attr, support)


def exported(p: InterfacePackage, kind: str) -> dict[str, str]:
    """Names `<pkg>.<kind>` exports → the interface whose module defines them."""
    out: dict[str, str] = {}
    for short in p.interfaces.get(kind, []):
        out[short] = short
        if kind == "srv":
            out.update({short + s: short for s in ("_Event", "_Request", "_Response")})
        elif kind == "action":
            out.update({f"{short}{svc}{s}": short for svc in ("_GetResult", "_SendGoal")
                        for s in ("_Event", "_Request", "_Response")})
    return out


def _types_of(kind: str, full: str) -> list[str]:
    if kind == "msg":
        return [full]
    if kind == "srv":
        return [full + s for s in ("_Request", "_Response", "_Event")]
    parts = [full + s for s in ("_Goal", "_Result", "_Feedback")]
    for svc in ("_SendGoal", "_GetResult"):
        parts += [full + svc + s for s in ("_Request", "_Response", "_Event")]
    return [*parts, full + "_FeedbackMessage"]


def fill_interface_module(module: types.ModuleType, p: InterfacePackage, kind: str, short: str) -> None:
    """Execute the generated source of interface `p.name/kind/short` into `module`."""
    full = f"{p.name}/{kind}/{short}"
    defs: dict[str, TypeDef] = {}
    for t in _types_of(kind, full):
        td = registry.lookup(t)
        if td is None:
            raise ImportError(f"{t} has no definition", name=module.__name__)
        defs[t] = td
    origin = str(p.files.get(full, f"diffctl's {full}"))
    for td in defs.values():
        for fname, _ in td.fields:
            if keyword.iskeyword(fname):
                # rosidl_adapter accepts it, but the property rosidl_generator_py writes for it is a SyntaxError
                raise InterfaceError(
                    f"{td.name}: field {fname!r} is a Python keyword, so its message class cannot be generated",
                    source=origin, line=td.lines.get(fname), field=fname, hint=f"rename it, e.g. {fname}_value")
    source = pysource.module_source(kind, full, defs, origin)
    filename = f"<{module.__name__} generated from {origin}>"
    linecache.cache[filename] = (len(source), None, source.splitlines(True), filename)
    exec(compiled(source, filename), module.__dict__)
    for t in defs:
        cls = module.__dict__[t.split("/")[-1]]
        NAMES[cls] = t
        CLASSES[t] = cls
    for svc in ([full] if kind == "srv" else [full + "_SendGoal", full + "_GetResult"] if kind == "action" else []):
        cls = module.__dict__[svc.split("/")[-1]]
        NAMES[cls] = svc
        CLASSES[svc] = cls
    if kind == "action":
        cls = module.__dict__[short]
        NAMES[cls] = full
        CLASSES[full] = cls


def kind_getattr(kind_module: types.ModuleType, p: InterfacePackage, kind: str) -> Any:
    names = exported(p, kind)

    def __getattr__(name: str) -> Any:
        short = names.get(name)
        if short is None:
            raise AttributeError(f"module '{p.name}.{kind}' has no attribute {name!r}")
        module = importlib.import_module(f"{p.name}.{kind}._{pysource.snake(short)}")
        value = getattr(module, name)
        # Kept in the module: the next `from pkg.msg import T` (every constructor has one) is a dict hit.
        setattr(kind_module, name, value)
        return value

    return __getattr__


def interface_class(typename: str) -> type:
    """The class of `pkg/kind/T` (or a part: `pkg/srv/T_Request`, `pkg/action/T_Goal`), importing its module."""
    cls = CLASSES.get(typename)
    if cls is not None:
        return cls
    pkg, kind, name = typename.split("/")
    p = registry.package(pkg)
    if p is None:
        raise ModuleNotFoundError(f"no interface package {pkg!r}: {registry.searched(pkg)}", name=pkg)
    shorts = p.interfaces.get(kind, [])
    short = name if name in shorts else next((s for s in shorts if name.startswith(s + "_")), None)
    if short is None:
        from diffctl.errors import suggest

        raise ImportError(f"package {pkg!r} ({p.origin}: {p.where}) has no {kind} {name!r}"
                          f"{suggest(name, shorts)}", name=f"{pkg}.{kind}")
    importlib.import_module(f"{pkg}.{kind}._{pysource.snake(short)}")
    cls = CLASSES.get(typename)
    if cls is None:
        raise ImportError(f"{typename} is not a type of {pkg}/{kind}/{short}", name=f"{pkg}.{kind}")
    return cls

