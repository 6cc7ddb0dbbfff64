"""SDF documents: reading files and strings, checking the version, and resolving `<include>`s of local models.

Every parsed document becomes a `Doc` (source, base directory, version, search path) that travels with its
elements, so errors deep inside an included model still name the right file and line.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from lxml import etree

from diffctl.description.lenient_xml import parse_lenient
from diffctl.description.pose import Pose
from diffctl.description.resources import is_remote, model_file_in, resolve_uri, search_path_for
from diffctl.description.sdf_values import (
    Doc,
    Element,
    child,
    child_text,
    fail,
    parse_bool,
    pose_child,
    required_attr,
)
from diffctl.errors import DescriptionError, xml_error

SUPPORTED_VERSIONS = ((1, 4), (1, 11))

# --- documents -------------------------------------------------------------------------------------------


def doc_from_bytes(
    data: bytes, source: str, base_dir: Path, search_path: tuple[Path, ...], check_files: bool
) -> tuple[Element, Doc]:
    try:
        root = parse_lenient(data)
    except etree.XMLSyntaxError as e:
        raise xml_error(e, source) from None
    placeholder = Doc(source, base_dir, (1, 11), search_path, check_files)
    if root.tag != "sdf":
        hint = "this looks like URDF; diffctl reads SDF (gz sdf -p converts)" if root.tag == "robot" else None
        fail(placeholder, root, f"the root element must be <sdf>, got <{root.tag}>", hint=hint)
    text = (root.get("version") or "").strip()
    try:
        major, minor = (int(p) for p in text.split("."))
    except ValueError:
        fail(placeholder, root, f'<sdf> needs version="1.x", got {text!r}', hint='e.g. <sdf version="1.8">')
    lo, hi = SUPPORTED_VERSIONS
    if not lo <= (major, minor) <= hi:
        fail(
            placeholder,
            root,
            f"SDF version {text} is not supported",
            hint=f"supported: {lo[0]}.{lo[1]} to {hi[0]}.{hi[1]}",
        )
    return root, Doc(source, base_dir, (major, minor), search_path, check_files)


def read_file(path: Path, search_path: tuple[Path, ...], check_files: bool) -> tuple[Element, Doc]:
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise DescriptionError("file not found", source=str(path)) from None
    except IsADirectoryError:
        raise DescriptionError("is a directory, not an SDF file", source=str(path)) from None
    except OSError as e:
        raise DescriptionError(f"cannot read: {e.strerror}", source=str(path)) from None
    base = path.resolve().parent
    # a workspace package's share tree links each file to its source: errors name the file the user edits
    shown = str(path.resolve()) if path.is_symlink() else str(path)
    return doc_from_bytes(data, shown, base, search_path or search_path_for(base), check_files)


def text_doc(
    text: str, source: str, base_dir: str | Path | None, search_path: tuple[str | Path, ...], check_files: bool
) -> tuple[Element, Doc]:
    base = Path(base_dir).resolve() if base_dir is not None else Path.cwd()
    # lxml refuses str input that carries an encoding declaration; bytes are always accepted.
    return doc_from_bytes(text.encode(), source, base, search_path_for(base, search_path), check_files)


def stack_key(doc: Doc) -> str:
    """The identity of a document on the include stack (resolved path; strings are unique by name)."""
    return doc.source if doc.source.startswith("<") else str(Path(doc.source).resolve())


# --- includes ----------------------------------------------------------------------------------------------


@dataclass
class Include:
    doc: Doc
    model_el: Element  # the included <model>, or <light> (a Fuel "Sun"): exactly one of them per file
    name: str
    pose: Pose | None
    pose_rel: str | None
    pose_el: Element | None
    static: bool | None
    placement: str | None
    merge: bool = False
    uri: str = ""

    @property
    def is_light(self) -> bool:
        return self.model_el.tag == "light"


_skipped: set[str] = set()  # Fuel models a world loaded without, each reported once per process


def _include_target(doc: Doc, uri: str, uri_el: Element) -> Path | None:
    """The file an include's URI names; None for a Fuel model the user chose to load the world without."""
    if is_remote(uri):
        from diffctl.fuel.resolve import SKIP_MISSING_ENV, FuelModelUnavailable, resolve_fuel, skip_missing

        try:
            target = resolve_fuel(uri)
        except FuelModelUnavailable as e:
            if skip_missing():
                if uri not in _skipped:
                    _skipped.add(uri)
                    from diffctl.console import warn
                    from diffctl.source_paths import user_source

                    warn(f"{user_source(doc.source)}:{uri_el.sourceline}: {e.message}; the world loads without it "
                         f"({e.hint}; {SKIP_MISSING_ENV}=0 makes this an error)")
                return None
            fail(doc, uri_el, e.message, hint=e.hint)
        except DescriptionError as e:
            fail(doc, uri_el, e.message, hint=e.hint)
        if target is None:
            fail(
                doc,
                uri_el,
                f"cannot include {uri!r}: only Fuel model URLs are fetched over the network",
                hint="e.g. https://fuel.gazebosim.org/1.0/<owner>/models/<name>[/<version>], a model:// URI or a path",
            )
    else:
        target = resolve_uri(uri, doc.base_dir, doc.search_path)
    if target is not None and target.is_dir():
        target = model_file_in(target)
    if target is None:
        searched = ", ".join(str(d) for d in doc.search_path)
        fail(doc, uri_el, f"included model {uri!r} not found", hint=f"searched {searched}; set GZ_SIM_RESOURCE_PATH")
    return target


def read_include(doc: Doc, inc: Element, stack: tuple[str, ...]) -> Include | None:
    """The included model (or light); None when it is a missing Fuel model the user chose to skip."""
    uri_el = child(inc, "uri")
    uri = (uri_el.text or "").strip() if uri_el is not None else ""
    if not uri:
        fail(doc, inc, "<include> needs a <uri>", hint="e.g. <uri>model://my_model</uri> or a relative path")
    target = _include_target(doc, uri, uri_el)
    if target is None:
        return None
    key = str(target.resolve())
    if key in stack:
        fail(doc, uri_el, f"include cycle: {' → '.join([*stack, key])}")
    root, inc_doc = read_file(target, doc.search_path, doc.check_files)
    tops = [c for c in root if c.tag in ("model", "light", "actor")]
    if len(tops) != 1:
        fail(inc_doc, root, f"an included file must hold exactly one <model> or <light>, found {len(tops)}")
    model_el = tops[0]
    if model_el.tag == "actor":
        fail(inc_doc, model_el, "included <actor>s are not simulated by diffctl", hint="include a <model> or <light>")
    merge = (inc.get("merge") or "").strip().lower() in ("true", "1")
    if merge and model_el.tag != "model":
        fail(doc, inc, f'<include merge="true"> needs a <model>, but {uri!r} holds a <{model_el.tag}>')
    pose_el = child(inc, "pose")
    pose, rel = (None, None)
    if pose_el is not None:
        pose, rel, _ = pose_child(doc, inc)
    static_el = child(inc, "static")
    static = parse_bool(doc, static_el, static_el.text or "") if static_el is not None else None
    name = child_text(inc, "name") or required_attr(inc_doc, model_el, "name")
    placement = child_text(inc, "placement_frame") or None
    return Include(inc_doc, model_el, name, pose, rel, pose_el, static, placement, merge, uri)
