"""Mesh files of a URDF: `package://`, `file://`, `model://`, absolute and relative URIs → a file PyBullet reads.

`package://pkg/path` resolves through diffctl's package index (the user's workspace first, as ROS would find
it); `model://name/path` through GZ_SIM_RESOURCE_PATH as Gazebo does; relative paths against the URDF's folder.
PyBullet reads OBJ and STL; a COLLADA (.dae) file is converted once to OBJ with trimesh into the user's cache.
A mesh that cannot be found is a MeshNotFound naming the URI and every place it was looked for (the
conversion leaves that shape out with an error, as Gazebo does).
"""

from __future__ import annotations

import hashlib
import os
import re
from pathlib import Path

from diffctl.description.missing_mesh import MeshNotFound
from diffctl.description.resources import env_search_path
from diffctl.errors import DescriptionError, DiffctlError

DIRECT_SUFFIXES = (".obj", ".stl")
CONVERTED_SUFFIXES = (".dae",)


def package_share(package: str) -> Path:
    """The share directory of a ROS package: the one place description code asks the package index."""
    from diffctl.workspace import share_dir

    return share_dir(package)


def _candidates(uri: str, base_dir: Path) -> tuple[list[Path], str | None]:
    """Paths `uri` may name, in order, and the reason none could be listed (an unknown package)."""
    if uri.startswith("package://"):
        package, _, rest = uri[len("package://") :].partition("/")
        # Gazebo rewrites package:// to model:// and searches GZ_SIM_RESOURCE_PATH: those places come after the
        # package index, so a setup that only exported the resource path keeps working.
        fallback = [d / package / rest for d in env_search_path()]
        try:
            return [package_share(package) / rest, *fallback], None
        except DiffctlError as e:
            return fallback, f"package {package!r} not found" + (f" ({e.hint})" if e.hint else "")
    if uri.startswith("model://"):
        rest = uri[len("model://") :]
        return [d / rest for d in env_search_path()], None
    path = Path(uri[len("file://") :] if uri.startswith("file://") else uri).expanduser()
    return ([path] if path.is_absolute() else [base_dir / path]), None


def cache_dir() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "diffctl" / "meshes"


def convert_to_obj(path: Path) -> Path:
    """A COLLADA mesh as OBJ in the cache, keyed by the file's path, size and modification time."""
    stat = path.stat()
    key = hashlib.sha256(f"{path.resolve()}|{stat.st_size}|{stat.st_mtime_ns}".encode()).hexdigest()[:24]
    out = cache_dir() / f"{path.stem}-{key}.obj"
    if out.is_file():
        return out
    import trimesh

    try:
        mesh = trimesh.load(str(path), force="mesh")
    except Exception as e:  # trimesh raises many types for unreadable files
        raise DescriptionError(f"mesh {path} cannot be read: {e}", source=str(path)) from None
    if mesh.units and mesh.units != "meters":
        mesh.convert_units("meters")  # COLLADA's <unit meter="…">, which Gazebo's loader applies too
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_suffix(f".{os.getpid()}.tmp")
    tmp.write_text(trimesh.exchange.obj.export_obj(mesh, include_normals=False))  # PyBullet computes its own
    tmp.replace(out)  # atomic: a concurrent loader never reads half a file
    return out


_FACE_LINE = re.compile(rb"(?m)^[ \t]*f[ \t]+[-+]?\d")
_checked: dict[tuple[Path, int, int], Path | None] = {}


def pybullet_mesh(path: Path) -> Path | None:
    """The file PyBullet should load for an OBJ or STL, or None when it holds no triangle.

    PyBullet reads binary STL only: an ASCII STL (common in ROS packages), or a binary one whose size disagrees
    with its triangle count, made it crash (segfault) as a collision; such files are converted to OBJ. A mesh
    with no triangle crashes it too, or fails its shape creation: there is nothing to simulate (the caller
    leaves the shape out)."""
    try:
        st = path.stat()
    except OSError:
        return path  # the loader reports a file that cannot be read
    key = (path, st.st_mtime_ns, st.st_size)
    if key in _checked:
        return _checked[key]
    out: Path | None = path
    if path.suffix.lower() == ".stl":
        with path.open("rb") as f:
            head = f.read(84)
        count = int.from_bytes(head[80:84], "little") if len(head) == 84 else -1
        if count < 0 or st.st_size != 84 + 50 * count:
            out = convert_to_obj(path)  # ASCII (or odd) STL: trimesh reads it
        elif count == 0:
            out = None
    if out is not None and out.suffix.lower() == ".obj" and not _FACE_LINE.search(out.read_bytes()):
        out = None
    _checked[key] = out
    return out


def resolve_mesh(uri: str, base_dir: Path, source: str, line: int | None) -> Path:
    """The file PyBullet should load for a URDF mesh URI (converted when PyBullet cannot read the format)."""
    candidates, problem = _candidates(uri, base_dir)
    found = next((c for c in candidates if c.is_file()), None)
    if found is None:
        looked = ", ".join(str(c) for c in candidates)
        if not looked and uri.startswith(("model://", "package://")):
            looked = "GZ_SIM_RESOURCE_PATH, which is empty"
        raise MeshNotFound(
            f"mesh {uri!r} not found" + (f": {problem}" if problem else ""),
            source=source,
            line=line,
            field="mesh",
            hint=f"looked in {looked}" if looked else None,
        )
    suffix = found.suffix.lower()
    if suffix in DIRECT_SUFFIXES:
        return found.resolve()
    if suffix in CONVERTED_SUFFIXES:
        return convert_to_obj(found.resolve())
    raise DescriptionError(
        f"mesh {uri!r} has format {suffix!r}",
        source=source,
        line=line,
        field="mesh",
        hint="supported: " + ", ".join(DIRECT_SUFFIXES + CONVERTED_SUFFIXES),
    )
