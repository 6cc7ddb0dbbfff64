"""Which interface packages exist and what they define, in ROS's order: workspace, install trees, diffctl's.

diffctl's own types are the bus's (rosbags' Jazzy store and the project's definitions, `diffctl.interfaces.typedefs`)
plus the Jazzy texts shipped beside this module (`jazzy/`: services, actions, example_interfaces, and the
messages whose fields have .msg defaults, which rosbags does not keep). The user's workspace packages
(`rosidl_generate_interfaces` in their CMakeLists) and install trees' `share/<pkg>/{msg,srv,action}` (.msg,
.srv, .action files, or .idl where an interface has only that) come
first: a package is taken whole from the first place that has it. Every definition served is also entered
in the bus's definitions, so the bus declares, hashes and (de)serializes those types like its own.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, field
from pathlib import Path

from rosbags.typesys.base import Nodetype

from diffctl.errors import suggest
from diffctl.interfaces import idl, typedefs
from diffctl.interfaces.idl import InterfaceError, TypeDef

JAZZY = Path(__file__).resolve().parent / "jazzy"
KINDS = ("msg", "srv", "action")
_EXT = {"msg": ".msg", "srv": ".srv", "action": ".action"}


@dataclass
class InterfacePackage:
    name: str
    origin: str  # "workspace", "AMENT_PREFIX_PATH", "COLCON_PREFIX_PATH" or "diffctl"
    where: str  # the folder (or "diffctl") it was read from
    interfaces: dict[str, list[str]] = field(default_factory=dict)  # kind → interface names, sorted
    files: dict[str, Path] = field(default_factory=dict)  # pkg/kind/Name → its file (not for rosbags' types)


_lock = threading.RLock()
_packages: dict[str, InterfacePackage | None] = {}
_types: dict[str, TypeDef] = {}
_diffctl_index: dict[str, InterfacePackage] | None = None


def diffctl_packages() -> dict[str, InterfacePackage]:
    """diffctl's own interface packages: the bus's definitions and the shipped Jazzy texts."""
    global _diffctl_index
    if _diffctl_index is None:
        index: dict[str, InterfacePackage] = {}
        for name in sorted(typedefs.own_names()):  # not what other packages entered there since
            pkg, kind, short = name.split("/")
            if kind == "srv":
                if not short.endswith("_Request"):
                    continue
                short = short[: -len("_Request")]
            p = index.setdefault(pkg, InterfacePackage(pkg, "diffctl", "diffctl"))
            p.interfaces.setdefault(kind, []).append(short)
        for path in sorted(JAZZY.glob("*/*/*.*")):
            pkg, kind = path.parent.parent.name, path.parent.name
            p = index.setdefault(pkg, InterfacePackage(pkg, "diffctl", "diffctl"))
            names = p.interfaces.setdefault(kind, [])
            if path.stem not in names:
                names.append(path.stem)
            p.files[f"{pkg}/{kind}/{path.stem}"] = path
        for p in index.values():
            p.interfaces = {k: sorted(v) for k, v in p.interfaces.items()}
        _diffctl_index = index
    return _diffctl_index


def _scan_share(share: Path, name: str, origin: str) -> InterfacePackage | None:
    p = InterfacePackage(name, origin, str(share))
    for kind in KINDS:
        d = share / kind
        if d.is_dir():
            files = list(d.glob("*" + _EXT[kind]))
            # rosidl installs each interface's .idl beside its .msg/.srv/.action; one declared as .idl has only that
            stems = {f.stem for f in files}
            files = sorted([*files, *(f for f in d.glob("*.idl") if f.stem not in stems)], key=lambda f: f.stem)
            if files:
                p.interfaces[kind] = [f.stem for f in files]
                p.files.update({f"{name}/{kind}/{f.stem}": f for f in files})
    return p if p.interfaces else None


def _install_tree_package(name: str) -> InterfacePackage | None:
    from diffctl.workspace.prefixes import install_prefixes

    for prefix in install_prefixes():
        found = _scan_share(prefix.path / "share" / name, name, prefix.origin)
        if found is not None:
            return found
    return None


def package(name: str) -> InterfacePackage | None:
    """The interface package `name` from the first place that has it (None: nowhere), its types loaded."""
    with _lock:
        if name in _packages:
            return _packages[name]
        from diffctl.interfaces import hook

        # The hook's standard-library checks first: most processes have no workspace package or install tree
        # of that name, and then never import the workspace reader (lxml, the CMake reader, …).
        found = None
        if hook.in_workspace(name):
            from diffctl.interfaces import workspace

            found = workspace.interface_package(name)
        if found is None and hook.in_install_trees(name):
            found = _install_tree_package(name)
        if found is None:
            found = diffctl_packages().get(name)
        _packages[name] = found
        if found is not None:
            try:
                _load(found)
            except BaseException:
                # Refused whole: a second import of it raises again instead of finding it half loaded.
                del _packages[name]
                for full in [t for t in _types if t.startswith(name + "/")]:
                    del _types[full]
                raise
        return found


def _load(p: InterfacePackage) -> None:
    defs = typedefs.definitions()
    loaded: list[TypeDef] = []
    if p.origin == "diffctl":
        for kind, names in p.interfaces.items():
            for short in names:
                full = f"{p.name}/{kind}/{short}"
                path = p.files.get(full)
                if path is not None:
                    loaded += idl.interface_defs(full, path.read_text(encoding="utf-8"), str(path))
                elif kind == "srv":
                    parts = [f"{full}_Request", f"{full}_Response", f"{full}_Event", full]
                    loaded += [TypeDef(n, *map(list, defs[n])) for n in parts]
                else:
                    loaded.append(TypeDef(full, *map(list, defs[full])))
    else:
        for full, path in p.files.items():
            try:
                text = path.read_text(encoding="utf-8")
            except OSError as e:
                raise InterfaceError(f"cannot read: {e.strerror}", source=str(path)) from None
            loaded += idl.interface_defs(full, text, str(path))
    for td in loaded:
        _types[td.name] = td
    # What they reference from other packages must be known before the bus can hash or encode them.
    for td in loaded:
        for dep in referenced_packages(td):
            if dep != p.name and package(dep) is None:
                where = p.files.get(td.name.rsplit("_", 1)[0]) or p.files.get(td.name)
                raise InterfaceError(
                    f"{td.name} uses a type of package {dep!r}, which is nowhere: {searched(dep)}",
                    source=str(where) if where else p.where)
    own = {td.name for td in loaded}
    for td in loaded:
        for fname, ref in referenced_types(td):
            ref_pkg = ref.split("/")[0]
            if ref in own or (ref_pkg != p.name and ref in _types):
                continue
            where = p.files.get(td.name.rsplit("_", 1)[0]) or p.files.get(td.name)
            others = [n for n in (*defs, *_types) if n.split("/")[2] == ref.split("/")[2]]
            if not others and ref_pkg != p.name:
                others = [n for n in _types if n.startswith(ref_pkg + "/msg/")]
            raise InterfaceError(
                f"{td.name}: field {fname!r} has type {ref}, which package {ref_pkg} does not define"
                f"{suggest(ref, others) if others else ''}", source=str(where) if where else p.where)
    # diffctl's own packages are Jazzy's definitions, which rosidl built (none contains itself): checked by the
    # tests, not at every process's start (the walk was a good part of loading a package).
    for td in loaded if p.origin != "diffctl" else ():
        cycle = _cycle_from(td.name, defs)
        if cycle:
            raise InterfaceError(
                f"{td.name} contains itself: {' → '.join(cycle)} (a ROS 2 interface cannot be recursive: "
                "rosidl's build fails on it; refer to the others by index or id instead)",
                **_field_place(p, td, cycle[0].rsplit(".", 1)[1]))
    for td in loaded:
        defs[td.name] = (td.constants, td.fields)


def _file_of(p: InterfacePackage, typename: str) -> Path | None:
    """The file defining `typename` (a service's and an action's parts are in the interface's file)."""
    found = p.files.get(typename)
    if found is None and "/" in typename and typename.split("/")[1] in ("srv", "action"):
        found = p.files.get(typename.rsplit("_", 1)[0])
    return found


def _field_place(p: InterfacePackage, td: TypeDef, fname: str) -> dict:
    where = _file_of(p, td.name)
    return {"source": str(where) if where else p.where, "line": td.lines.get(fname), "field": fname}


def _cycle_from(start: str, defs: dict) -> list[str]:
    """`Type.field` steps from `start` back to itself through message fields (arrays and sequences
    included), or [] when the type does not contain itself."""

    def fields_of(name: str) -> list:
        td = _types.get(name)
        if td is not None:
            return td.fields
        return defs[name][1] if name in defs else []

    trail: list[str] = []
    visited: set[str] = set()

    def walk(name: str) -> bool:
        for fname, ref in referenced_types(TypeDef(name, fields=fields_of(name))):
            trail.append(f"{name}.{fname}")
            if ref == start:
                return True
            if ref not in visited:
                visited.add(ref)
                if walk(ref):
                    return True
            trail.pop()
        return False

    return [*trail, start] if walk(start) else []


def referenced_types(td: TypeDef) -> list[tuple[str, str]]:
    """(field, pkg/msg/Type) of every field of a message type (or of arrays of one)."""
    out = []
    for name, desc in td.fields:
        while desc[0] in (Nodetype.ARRAY, Nodetype.SEQUENCE):
            desc = desc[1][0]
        if desc[0] == Nodetype.NAME:
            out.append((name, desc[1]))
    return out


def referenced_packages(td: TypeDef) -> set[str]:
    return {ref.split("/")[0] for _, ref in referenced_types(td)}


def lookup(typename: str) -> TypeDef | None:
    """The definition of one message type (`pkg/msg/T`, `pkg/srv/T_Request`, `pkg/action/T_Goal`, …)."""
    td = _types.get(typename)
    if td is None and package(typename.split("/")[0]) is not None:
        td = _types.get(typename)
    return td


def searched(name: str) -> str:
    """Where a package was looked for, for the error that says it is nowhere."""
    from diffctl.interfaces import workspace
    from diffctl.workspace.prefixes import install_prefixes

    places = [workspace.describe()]
    prefixes = install_prefixes()
    if prefixes:
        places.append("install trees " + ", ".join(f"{p.path}/share/{name}" for p in prefixes))
    else:
        places.append("install trees (AMENT_PREFIX_PATH and COLCON_PREFIX_PATH are empty)")
    places.append(f"diffctl's types ({len(diffctl_packages())} packages)")
    return "; ".join(places)


def all_package_names() -> list[str]:
    from diffctl.interfaces import workspace

    return sorted({*diffctl_packages(), *workspace.interface_package_names()})


def reset() -> None:
    """Forget what was loaded (tests that build workspaces)."""
    global _diffctl_index
    with _lock:
        _packages.clear()
        _types.clear()
        _diffctl_index = None
