"""Where message definitions come from: rosbags' Jazzy store plus the project's .msg/.srv text, cached.

Building rosbags' whole Jazzy store defines ~250 dataclasses — about 80 ms on an idle machine and far more
on a busy one — in every process, and parsing the project's .msg text costs more. So the definitions are
computed once and cached as JSON under the user's cache directory, keyed by the rosbags version and the
project's interface text; a process then registers only the types it uses, with their dependencies.
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
import threading
from pathlib import Path
from typing import Any

from rosbags.typesys.base import Nodetype

FORMAT = 3  # 2: every char is uint8, as rosidl has it; 3: empty structures carry rosidl's placeholder member
_defs: dict[str, tuple[list, list]] | None = None
_own: frozenset[str] = frozenset()
_lock = threading.Lock()


def _cache_file() -> Path:
    from diffctl.interfaces import extra_texts as interfaces

    h = hashlib.sha256()
    # rosbags' Jazzy store as installed (a stat, not importlib.metadata: 15 ms of every process's start)
    import importlib.util

    spec = importlib.util.find_spec("rosbags.typesys.stores.ros2_jazzy")
    st = os.stat(spec.origin) if spec and spec.origin else None
    h.update(f"{FORMAT}/{spec and spec.origin}/{st and st.st_size}/{st and st.st_mtime_ns}/".encode())
    h.update(Path(interfaces.__file__).read_bytes())
    h.update(repr((interfaces.MSGS, interfaces.SRVS)).encode())  # the texts read from interface_texts/
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "diffctl"
    return base / f"typedefs-jazzy-{h.hexdigest()[:16]}.json"


def _char_as_uint8(desc: tuple) -> tuple:
    kind, spec = desc
    if kind == Nodetype.BASE:
        return (kind, ("uint8", spec[1])) if spec[0] == "char" else desc
    if kind in (Nodetype.ARRAY, Nodetype.SEQUENCE):
        return (kind, (_char_as_uint8(spec[0]), spec[1]))
    return desc


def patch_chars(fielddefs: dict[str, Any]) -> None:
    """rosidl turns a .msg `char` into IDL uint8; rosbags keeps it as char, which changes the RIHS01 hash of
    std_msgs/Char, rmw_dds_common/Gid and every service (its event carries ServiceEventInfo.client_gid).
    Same wire size, so the patch is safe."""
    for name, (consts, flds) in list(fielddefs.items()):
        fielddefs[name] = (
            [(c[0], "uint8" if c[1] == "char" else c[1], c[2]) for c in consts],
            [(n, _char_as_uint8(t)) for n, t in flds],
        )


EMPTY_MEMBER = "structure_needs_at_least_one_member"


def pad_empty(fielddefs: dict[str, Any]) -> None:
    """rosidl gives a structure without members (an empty .msg, most service requests) one `uint8` named
    structure_needs_at_least_one_member, so it is one byte on the wire and in its type hash; rosbags' parser
    leaves such a .msg text without fields (its Jazzy store has the member)."""
    for name, (consts, flds) in list(fielddefs.items()):
        if not flds:
            fielddefs[name] = (consts, [(EMPTY_MEMBER, (Nodetype.BASE, ("uint8", 0)))])


def srv_typesdict(name: str, req_text: str, resp_text: str) -> dict[str, Any]:
    """Request, response, event and the wrapper whose RIHS01 hash is the service's, as rosidl defines them."""
    from rosbags.typesys import get_types_from_msg

    pkg, _, short = name.split("/")
    out: dict[str, Any] = {}
    for suffix, text in (("Request", req_text), ("Response", resp_text)):
        for k, v in get_types_from_msg(text, f"{pkg}/msg/{short}_{suffix}").items():
            out[k.replace(f"{pkg}/msg/{short}_", f"{name}_")] = v
    n = Nodetype
    out[f"{name}_Event"] = ([], [
        ("info", (n.NAME, "service_msgs/msg/ServiceEventInfo")),
        ("request", (n.SEQUENCE, ((n.NAME, f"{name}_Request"), 1))),
        ("response", (n.SEQUENCE, ((n.NAME, f"{name}_Response"), 1))),
    ])
    out[name] = ([], [
        ("request_message", (n.NAME, f"{name}_Request")),
        ("response_message", (n.NAME, f"{name}_Response")),
        ("event_message", (n.NAME, f"{name}_Event")),
    ])
    return out


def _build() -> dict[str, tuple[list, list]]:
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    from diffctl.interfaces.extra_texts import MSGS, SRVS

    defs: dict[str, Any] = dict(get_typestore(Stores.ROS2_JAZZY).fielddefs)
    patch_chars(defs)
    for name, text in MSGS.items():
        defs.update(get_types_from_msg(text, name))
    for name, (req, resp) in SRVS.items():
        defs.update(srv_typesdict(name, req, resp))
    pad_empty(defs)
    return defs


def _desc(d: list) -> tuple:
    kind = Nodetype(d[0])
    if kind == Nodetype.BASE:
        return (kind, (d[1][0], d[1][1]))
    if kind == Nodetype.NAME:
        return (kind, d[1])
    return (kind, (_desc(d[1][0]), d[1][1]))


def _decode(raw: dict[str, Any]) -> dict[str, tuple[list, list]]:
    return {
        name: ([(c[0], c[1], c[2]) for c in consts], [(f[0], _desc(f[1])) for f in flds])
        for name, (consts, flds) in raw.items()
    }


def definitions() -> dict[str, tuple[list, list]]:
    """Every known type's rosbags field definitions: from the cache, or built (and cached) once. Interface
    packages read later (diffctl.interfaces' registry: a workspace's, install trees') are added here."""
    global _defs, _own
    if _defs is None:
        with _lock:
            if _defs is None:
                path = _cache_file()
                try:
                    defs = _decode(json.loads(path.read_text()))
                except (OSError, ValueError, KeyError, IndexError, TypeError):
                    defs = _build()
                    _write(path, defs)
                _own = frozenset(defs)
                _defs = defs
    return _defs


def own_names() -> frozenset[str]:
    """The types diffctl defines itself (rosbags' Jazzy store and interfaces.py), not those added later."""
    definitions()
    return _own


def _write(path: Path, defs: dict[str, Any]) -> None:
    # Atomic: processes starting together may all build it; each renames a complete file into place.
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile("w", dir=path.parent, delete=False, suffix=".tmp") as f:
            json.dump(defs, f)
        os.replace(f.name, path)
    except OSError:
        pass  # a read-only home only costs the next process the build again


def closure(defs: dict[str, tuple[list, list]], names: list[str]) -> list[str]:
    """`names` and every type they reference, dependencies first."""
    out: list[str] = []
    seen: set[str] = set()

    def visit(name: str) -> None:
        if name in seen or name not in defs:
            return
        seen.add(name)
        for _, desc in defs[name][1]:
            while desc[0] in (Nodetype.ARRAY, Nodetype.SEQUENCE):
                desc = desc[1][0]
            if desc[0] == Nodetype.NAME:
                visit(desc[1])
        out.append(name)

    for n in names:
        visit(n)
    return out
