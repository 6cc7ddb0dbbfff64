"""The user's workspace interface packages: the files each CMakeLists passes to `rosidl_generate_interfaces`.

Read from the sources without building, with diffctl's CMake reader (variables, lists, globs and
subdirectories are followed as for install rules). `rosidl_generate_interfaces(<target> files…
[DEPENDENCIES pkgs…] [LIBRARY_NAME n] [ADD_LINTER_TESTS] [SKIP_INSTALL] …)`: every file names one interface,
`<pkg>/<msg|srv|action>/<stem>` by its extension (an .idl file by its folder), as rosidl_cmake does.
"""

from __future__ import annotations

from pathlib import Path

from diffctl.interfaces.idl import InterfaceError
from diffctl.interfaces.registry import InterfacePackage
from diffctl.workspace.cmake_script import Call, Script
from diffctl.workspace.discovery import find_workspace
from diffctl.workspace.resolve import scan_workspace

_KEYWORDS = {"DEPENDENCIES", "LIBRARY_NAME", "ADD_LINTER_TESTS", "SKIP_INSTALL", "SKIP_GROUP_MEMBERSHIP_CHECK"}
_KIND_OF = {".msg": "msg", ".srv": "srv", ".action": "action"}

_cache: dict[tuple[str, str], InterfacePackage | None] = {}


def _interfaces_of(pkg_dir: Path, name: str) -> InterfacePackage | None:
    lists = pkg_dir / "CMakeLists.txt"
    if not lists.is_file() or "rosidl_generate_interfaces" not in lists.read_text(errors="replace"):
        return None
    found = InterfacePackage(name, "workspace", str(pkg_dir))

    def on_call(call: Call) -> None:
        if call.name != "rosidl_generate_interfaces" or not call.args:
            return
        for arg in call.args[1:]:
            if arg in _KEYWORDS:
                break
            # `base:relative` names a file relative to `base`, as rosidl_cmake's idl tuples do.
            base, sep, rel = arg.rpartition(":")
            path = Path(rel) if sep and len(base) > 1 else Path(arg)
            root = Path(base) if sep and len(base) > 1 else call.current_dir
            full = path if path.is_absolute() else root / path
            # an .idl file's kind is its folder's name, as rosidl_cmake takes it
            kind = _KIND_OF.get(full.suffix) or (full.parent.name if full.suffix == ".idl" else None)
            where = {"source": str(call.source), "line": call.line}
            if kind not in _KIND_OF.values():
                raise InterfaceError(
                    f"rosidl_generate_interfaces: {arg!r} is not a .msg, .srv or .action file"
                    + (", nor an .idl file in a msg, srv or action folder" if full.suffix == ".idl" else ""),
                    **where)
            if not full.is_file():
                raise InterfaceError(f"rosidl_generate_interfaces: {arg!r} does not exist ({full})", **where)
            names = found.interfaces.setdefault(kind, [])
            if full.stem not in names:
                names.append(full.stem)
            found.files[f"{name}/{kind}/{full.stem}"] = full

    Script(pkg_dir, on_call).run_file(lists)
    found.interfaces = {k: sorted(v) for k, v in found.interfaces.items()}
    return found if found.interfaces else None


def _workspace_root() -> Path | None:
    try:
        return find_workspace()
    except Exception:  # a bad $DIFFCTL_WORKSPACE is reported by the commands that use it, not by imports
        return None


def interface_package(name: str) -> InterfacePackage | None:
    """The workspace's interface package `name`, or None when the workspace has none of that name."""
    root = _workspace_root()
    if root is None:
        return None
    key = (str(root), name)
    if key not in _cache:
        scan = scan_workspace(root)
        manifest = scan.manifests.get(name)
        _cache[key] = _interfaces_of(manifest.path.parent, name) if manifest is not None else None
    return _cache[key]


def interface_package_names() -> list[str]:
    root = _workspace_root()
    if root is None:
        return []
    return sorted(n for n in scan_workspace(root).manifests if interface_package(n) is not None)


def describe() -> str:
    root = _workspace_root()
    return f"workspace {root}/src" if root is not None else "no workspace (none enclosing the current directory)"


def reset() -> None:
    _cache.clear()
