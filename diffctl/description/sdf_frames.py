"""SDF 1.7+ frame semantics for one top-level model: scopes, `relative_to` chains, `attached_to`, `__model__`.

Every frame-bearing element (model, nested model, link, joint, frame) is a node with a raw pose and the node
its pose is relative to; resolving walks the chain to the top-level model frame. Names are looked up in the
scope of the element that names them (a nested model's scope, or the parent's, reaching inside with
`inner::name`); nested nodes get scoped keys `outer::inner::link`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from diffctl.description.pose import Pose
from diffctl.description.sdf_values import Doc, Element, fail
from diffctl.errors import suggest

MODEL_FRAME = "__model__"


@dataclass
class Node:
    key: str  # scoped name; MODEL_FRAME for the top-level model
    kind: str  # model | link | joint | frame
    raw: Pose
    doc: Doc
    el: Element
    relative_to: str | None = None  # node key, set when references are resolved
    attached_to: str | None = None  # frames: node key; joints: child link key; models: canonical link key
    placement: str | None = None  # nested models: key of the placement frame
    relative_ref: str | None = None  # unresolved text, for error messages
    pose_el: Element | None = None


@dataclass
class Scope:
    prefix: str  # "" for the top-level model, "inner::" inside nested model "inner"
    model_key: str
    names: dict[str, str] = field(default_factory=dict)  # local name → node key
    children: dict[str, Scope] = field(default_factory=dict)
    canonical: str | None = None  # link key
    merged: list[Scope] = field(default_factory=list)  # views of this scope for `<include merge="true">`d models

    def merged_view(self, proxy_key: str) -> Scope:
        """This scope's namespace, seen from a merged-in model: its `__model__` is the proxy frame."""
        view = Scope(prefix=self.prefix, model_key=proxy_key, names=self.names, children=self.children)
        self.merged.append(view)
        return view

    def lookup(self, ref: str) -> str | None:
        if ref == MODEL_FRAME:
            return self.model_key
        if ref in self.names:
            return self.names[ref]
        head, sep, rest = ref.partition("::")
        if sep and head in self.children:
            return self.children[head].lookup(rest)
        return None

    def all_names(self) -> list[str]:
        out = [MODEL_FRAME, *self.names]
        for name, sub in self.children.items():
            out += [f"{name}::{n}" for n in sub.all_names() if n != MODEL_FRAME]
        return out


class FrameGraph:
    """The frames of one top-level model and their poses in that model's frame."""

    def __init__(self) -> None:
        self.nodes: dict[str, Node] = {}
        self._memo: dict[str, Pose] = {}

    def add(self, node: Node, scope: Scope, local_name: str) -> None:
        if local_name in scope.names or local_name == MODEL_FRAME:
            other = self.nodes.get(scope.names.get(local_name, ""))
            where = f" (first at line {other.el.sourceline})" if other is not None else ""
            fail(
                node.doc,
                node.el,
                f"name {local_name!r} is used twice in one model{where}",
                hint="links, joints, frames and nested models share one namespace",
            )
        if "::" in local_name or local_name.startswith("__"):
            fail(
                node.doc,
                node.el,
                f"name {local_name!r} is reserved",
                hint="names may not contain '::' or start with '__'",
            )
        scope.names[local_name] = node.key
        self.nodes[node.key] = node

    def resolve_ref(self, scope: Scope, ref: str, doc: Doc, el: Element, what: str) -> str:
        key = scope.lookup(ref)
        if key is None:
            fail(
                doc,
                el,
                f"{what} {ref!r} names no frame in this model{suggest(ref, scope.all_names())}",
                hint="valid: " + ", ".join(scope.all_names()),
            )
        return key

    def pose_in(self, key: str, base: str) -> Pose:
        """The pose of `key` relative to `base`, following relative_to links until `base` (must be reached)."""
        pose = Pose()
        seen: list[str] = []
        while key != base:
            if key in seen:
                self._cycle(seen, key)
            seen.append(key)
            node = self.nodes[key]
            pose = self._effective_raw(node).compose(pose)
            if node.relative_to is None:
                raise AssertionError(f"frame chain from {seen[0]!r} never reaches {base!r}")
            key = node.relative_to
        return pose

    def pose_model(self, key: str) -> Pose:
        """The pose of node `key` in the top-level model frame."""
        if key == MODEL_FRAME:
            return Pose()
        if key in self._memo:
            return self._memo[key]
        chain: list[str] = []
        k = key
        while k != MODEL_FRAME and k not in self._memo:
            if k in chain:
                self._cycle(chain, k)
            chain.append(k)
            nxt = self.nodes[k].relative_to
            if nxt is None:
                raise AssertionError(f"node {k!r} has no relative_to")
            k = nxt
        base = Pose() if k == MODEL_FRAME else self._memo[k]
        for k in reversed(chain):
            base = base.compose(self._effective_raw(self.nodes[k]))
            self._memo[k] = base
        return self._memo[key]

    def _effective_raw(self, node: Node) -> Pose:
        # With a placement frame the written pose places that frame; the model frame sits at pose ∘ placement⁻¹.
        if node.placement is None:
            return node.raw
        return node.raw.compose(self.pose_in(node.placement, node.key).inverse())

    def _cycle(self, chain: list[str], again: str) -> None:
        node = self.nodes[chain[0]]
        loop = " → ".join([*chain[chain.index(again) :], again])
        fail(node.doc, node.pose_el if node.pose_el is not None else node.el, f"relative_to cycle: {loop}")

    def link_of(self, key: str) -> str:
        """The link a frame is rigidly attached to (links: themselves; joints: their child; models: canonical)."""
        seen: set[str] = set()
        while True:
            node = self.nodes[key]
            if node.kind == "link":
                return key
            if key in seen or node.attached_to is None:
                loop = " → ".join(sorted(seen | {key}))
                fail(node.doc, node.el, f"attached_to cycle or dangling frame: {loop}")
            seen.add(key)
            key = node.attached_to
