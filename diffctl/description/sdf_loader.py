"""Load SDF 1.6–1.11 worlds and models as Gazebo reads them, into `model.World` / `model.Model`.

Public API: `load_world(path)`, `load_model(path)`, `parse_world(text)`, `parse_model(text)`, `load(path)`.
Poses are resolved with SDF 1.7+ semantics (`relative_to`, `<frame attached_to>`, `__model__`, joint poses
in the child frame, `placement_frame`); nested models and `<include>`d local models are flattened with scoped
names. Any problem raises DescriptionError naming the file, the line and the element.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from diffctl.description.model import Light, Model, World
from diffctl.description.pose import Pose
from diffctl.description.resources import search_path_for
from diffctl.description.sdf_documents import Include, read_file, read_include, stack_key, text_doc
from diffctl.description.sdf_elements import parse_light, parse_physics, parse_plugin, parse_spherical_coordinates
from diffctl.description.sdf_model import build_model
from diffctl.description.sdf_values import Doc, Element, child, children, fail, pose_child, required_attr
from diffctl.errors import suggest

__all__ = ["load", "load_model", "load_world", "parse_model", "parse_world"]

# --- public API ------------------------------------------------------------------------------------------


def _model_from_root(root: Element, doc: Doc, name: str | None, pose: Pose | None, static: bool | None) -> Model:
    models = children(root, "model")
    if not models:
        hint = (
            "this file holds a <world>: use load_world / `diffctl sim run`"
            if child(root, "world") is not None
            else None
        )
        fail(doc, root, "no <model> in this SDF", hint=hint)
    if len(models) > 1:
        fail(doc, models[1], f"expected one <model>, found {len(models)}")
    el = models[0]
    model_name = name or required_attr(doc, el, "name")
    return build_model(
        doc, el, name=model_name, parent_world=Pose(), static=static, stack=(stack_key(doc),), pose_override=pose
    )


def included_light(inc: Include) -> Light:
    """A <light> from an included file (Fuel's "Sun"), with the include's <name> and <pose> applied."""
    light = parse_light(inc.doc, inc.model_el, Pose())
    pose = inc.pose if inc.pose is not None else light.pose_world
    return replace(light, name=inc.name, pose_world=pose)


def _world_from_root(root: Element, doc: Doc) -> World:
    worlds = children(root, "world")
    if not worlds:
        hint = "this file holds a <model>: spawn it into a world" if child(root, "model") is not None else None
        fail(doc, root, "no <world> in this SDF", hint=hint)
    w = worlds[0]
    world_name = required_attr(doc, w, "name")
    physics = parse_physics(doc, w)

    # World-level frames: models, <frame>s and "world"; a model's pose may be relative_to another of them.
    entries: dict[str, tuple[Pose, str | None, Doc, Element]] = {}
    pending: list[tuple[str, Doc, Element, Include | None]] = []
    lights = []
    plugins = [parse_plugin(doc, p) for p in children(w, "plugin")]
    # (document, element, offset): a merged include's models sit in the frame its <pose> gives.
    todo: list[tuple[Doc, Element, Pose | None]] = [(doc, c, None) for c in w]
    while todo:
        d, c, offset = todo.pop(0)
        if c.tag not in ("model", "include", "frame"):
            if offset is not None and c.tag == "plugin":
                plugins.append(parse_plugin(d, c))
            elif offset is not None and c.tag in ("link", "joint", "gripper"):
                fail(d, c, f"a <{c.tag}> cannot be merged into a world", hint='merge="true" into a world takes models')
            continue
        if c.tag == "include":
            inc = read_include(d, c, (stack_key(doc),))
            if inc is None:
                continue  # a missing Fuel model the user chose to do without (reported once)
            if inc.is_light:
                lights.append(included_light(inc))
                continue
            nm, pose, rel = inc.name, inc.pose or Pose(), inc.pose_rel
            if inc.pose is None:
                pose, rel, _ = pose_child(inc.doc, inc.model_el)
            if inc.merge:
                if rel is not None:
                    fail(d, c, 'relative_to on a world\'s <include merge="true"> is not supported by diffctl')
                base = offset.compose(pose) if offset is not None else pose
                todo[:0] = [(inc.doc, e, base) for e in inc.model_el] + [(d, p, base) for p in children(c, "plugin")]
                continue
        else:
            inc = None
            nm = required_attr(d, c, "name")
            pose, rel, _ = pose_child(d, c)
            if c.tag == "frame" and rel is None:
                rel = (c.get("attached_to") or "").strip() or None
        if offset is not None:
            if rel is not None:
                fail(d, c, 'relative_to inside a world\'s <include merge="true"> is not supported by diffctl')
            pose = offset.compose(pose)
        if nm in entries or nm == "world":
            fail(d, c, f"name {nm!r} is used twice in world {world_name!r}")
        entries[nm] = (pose, rel, d, c)
        if c.tag != "frame":
            pending.append((nm, d, c, inc))
    resolved: dict[str, Pose] = {"world": Pose()}

    def world_pose(nm: str, trail: tuple[str, ...]) -> Pose:
        if nm in resolved:
            return resolved[nm]
        pose, rel, d, el = entries[nm]
        if nm in trail:
            fail(d, el, f"relative_to cycle: {' → '.join([*trail, nm])}")
        base = Pose()
        if rel is not None:
            if rel not in entries and rel != "world":
                fail(
                    d, el, f"relative_to {rel!r} names no model or frame of world {world_name!r}{suggest(rel, entries)}"
                )
            base = world_pose(rel, (*trail, nm))
        # A model's own pose is applied by _build_model; here only its parent frame matters.
        resolved[nm] = base.compose(pose)
        return resolved[nm]

    models = []
    for nm, d, c, inc in pending:
        pose, rel, _, _ = entries[nm]
        parent = world_pose(rel, (nm,)) if rel is not None else Pose()
        if inc is not None:
            models.append(
                build_model(
                    inc.doc,
                    inc.model_el,
                    name=nm,
                    parent_world=parent,
                    static=inc.static,
                    stack=(stack_key(doc), stack_key(inc.doc)),
                    pose_override=pose,
                    placement=inc.placement,
                    extra_plugins=tuple((d, p) for p in children(c, "plugin")),
                )
            )
        else:
            models.append(
                build_model(
                    d, c, name=nm, parent_world=parent, static=None, stack=(stack_key(doc),), pose_override=pose
                )
            )
        resolved[nm] = models[-1].pose_world  # placement frames can move it: later references see the result
    lights = tuple(parse_light(doc, c, Pose()) for c in children(w, "light")) + tuple(lights)
    return World(
        world_name, physics, tuple(models), lights, tuple(plugins), doc.source, parse_spherical_coordinates(doc, w)
    )


def load_world(path: str | Path, *, search_path: tuple[str | Path, ...] = (), check_files: bool = True) -> World:
    """The first <world> of an SDF file."""
    p = Path(path)
    root, doc = read_file(p, search_path_for(p.resolve().parent, search_path), check_files)
    return _world_from_root(root, doc)


def load_model(
    path: str | Path,
    *,
    name: str | None = None,
    pose: Pose | None = None,
    static: bool | None = None,
    search_path: tuple[str | Path, ...] = (),
    check_files: bool = True,
) -> Model:
    """The one <model> of an SDF file; `name`/`pose`/`static` override what the file says (as spawn does)."""
    p = Path(path)
    root, doc = read_file(p, search_path_for(p.resolve().parent, search_path), check_files)
    return _model_from_root(root, doc, name, pose, static)


def parse_world(
    text: str,
    *,
    source: str = "<string>",
    base_dir: str | Path | None = None,
    search_path: tuple[str | Path, ...] = (),
    check_files: bool = True,
) -> World:
    root, doc = text_doc(text, source, base_dir, search_path, check_files)
    return _world_from_root(root, doc)


def parse_model(
    text: str,
    *,
    source: str = "<string>",
    name: str | None = None,
    pose: Pose | None = None,
    static: bool | None = None,
    base_dir: str | Path | None = None,
    search_path: tuple[str | Path, ...] = (),
    check_files: bool = True,
) -> Model:
    """A model from SDF text (e.g. a /robot_description); relative URIs resolve against `base_dir` (default cwd)."""
    root, doc = text_doc(text, source, base_dir, search_path, check_files)
    return _model_from_root(root, doc, name, pose, static)


def load(path: str | Path, *, search_path: tuple[str | Path, ...] = (), check_files: bool = True) -> World | Model:
    """Whatever the file holds: its <world> if it has one, else its <model>."""
    p = Path(path)
    root, doc = read_file(p, search_path_for(p.resolve().parent, search_path), check_files)
    if child(root, "world") is not None:
        return _world_from_root(root, doc)
    return _model_from_root(root, doc, None, None, None)
