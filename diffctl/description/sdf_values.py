"""Typed values read from SDF elements, every failure a DescriptionError naming file, line and element.

`Doc` carries what an element alone does not know: the file it came from, its SDF version and where to look for
`model://` resources. Helpers here never return half-parsed values: a bad number, an empty `<pose/>`, a size
that is not positive all stop the load with the offending text quoted.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import NoReturn

from lxml import etree

from diffctl.description.pose import Pose, quat_from_rpy, quat_normalize
from diffctl.errors import DescriptionError

Element = etree._Element


@dataclass(frozen=True)
class Doc:
    """One parsed SDF file (or string): where its elements came from and how to resolve its URIs."""

    source: str  # file path, or "<string>"
    base_dir: Path  # relative URIs resolve here
    version: tuple[int, int]
    search_path: tuple[Path, ...] = ()
    check_files: bool = True  # False: unresolvable mesh URIs are kept (path "") instead of failing
    # True for a URDF read for its kinematics (robot_state_publisher): urdfdom checks no physical value (inertia,
    # a zero joint axis), so only what sdformat would refuse *for the simulator* is skipped
    kinematics_only: bool = False

    @property
    def frames_v17(self) -> bool:
        """SDF 1.7+ frame semantics (relative_to, expressed_in); older files use the 1.6 defaults."""
        return self.version >= (1, 7)


def element_path(el: Element) -> str:
    """'model[car]/link[chassis]/pose': the element and its ancestors, with their name attributes."""
    parts = []
    node: Element | None = el
    while node is not None and isinstance(node.tag, str) and node.tag != "sdf":
        name = node.get("name")
        parts.append(f"{node.tag}[{name}]" if name else str(node.tag))
        node = node.getparent()
    return "/".join(reversed(parts))


def fail(doc: Doc, el: Element | None, message: str, hint: str | None = None) -> NoReturn:
    raise DescriptionError(
        message,
        source=doc.source,
        line=el.sourceline if el is not None else None,
        field=element_path(el) if el is not None else None,
        hint=hint,
    )


def children(el: Element, tag: str) -> list[Element]:
    return [c for c in el if c.tag == tag]


def child(el: Element, tag: str) -> Element | None:
    for c in el:
        if c.tag == tag:
            return c
    return None


def text_of(el: Element | None, default: str | None = None) -> str | None:
    if el is None:
        return default
    return (el.text or "").strip()


def child_text(el: Element, tag: str, default: str | None = None) -> str | None:
    return text_of(child(el, tag), default)


def required_attr(doc: Doc, el: Element, attr: str) -> str:
    value = (el.get(attr) or "").strip()
    if not value:
        fail(doc, el, f"<{el.tag}> needs a non-empty '{attr}' attribute")
    return value


def parse_floats(doc: Doc, el: Element, n: int | tuple[int, ...], what: str = "") -> tuple[float, ...]:
    """The element's text as `n` finite numbers (n may list several accepted counts)."""
    counts = (n,) if isinstance(n, int) else n
    raw = (el.text or "").split()
    expect = " or ".join(str(c) for c in counts)
    if len(raw) not in counts:
        shown = f"{(el.text or '').strip()!r}" if raw else "nothing"
        fail(doc, el, f"<{el.tag}> {what or 'needs'} {expect} numbers, got {shown}")
    try:
        values = tuple(float(x) for x in raw)
    except ValueError:
        fail(doc, el, f"<{el.tag}> must hold {expect} numbers, got {(el.text or '').strip()!r}")
    if not all(math.isfinite(v) for v in values):
        fail(doc, el, f"<{el.tag}> must hold finite numbers, got {(el.text or '').strip()!r}")
    return values


_C_DOUBLE = re.compile(
    r"[+-]?(?:inf(?:inity)?|nan|0x(?:[0-9a-f]+\.?[0-9a-f]*|\.[0-9a-f]+)(?:p[+-]?\d+)?|(?:\d+\.?\d*|\.\d+)(?:e[+-]?\d+)?)",
    re.IGNORECASE,
)
_C_INT = re.compile(r"[+-]?(?:0x[0-9a-f]+|\d+)", re.IGNORECASE)


def c_double(text: str) -> float | None:
    """A number as sdformat reads a double: std::stod of the trimmed text, i.e. the longest number it starts
    with ("0.5m" is 0.5), hex floats included; "true"/"false" are 1 and 0. None when it starts with none."""
    t = text.strip()
    if t.lower() in ("true", "false"):
        return float(t.lower() == "true")
    m = _C_DOUBLE.match(t)
    if m is None:
        return None
    number = m.group(0)
    return float.fromhex(number) if "x" in number.lower() else float(number)


def c_int(text: str) -> int | None:
    """An integer as sdformat reads one: std::stoi's leading integer ("10.0" is 10), base 16 after "0x";
    "true"/"false" are 1 and 0."""
    t = text.strip()
    if t.lower() in ("true", "false"):
        return int(t.lower() == "true")
    m = _C_INT.match(t)
    if m is None:
        return None
    number = m.group(0)
    return int(number, 16) if "x" in number.lower() else int(number)


def float_value(
    doc: Doc,
    parent: Element,
    tag: str,
    default: float | None = None,
    *,
    minimum: float | None = None,
    positive: bool = False,
    allow_inf: bool = False,
) -> float:
    """A single number from child `tag`; missing → default (None → error). Range checks quote the value."""
    el = child(parent, tag)
    if el is None:
        if default is None:
            fail(doc, parent, f"<{parent.tag}> needs a <{tag}> element")
        return default
    text = (el.text or "").strip()
    if not text and default is not None:
        return default  # sdformat: an empty optional element takes its default
    value = c_double(text)
    if value is None:
        fail(doc, el, f"<{tag}> must be a number, got {text!r}")
    if math.isnan(value) or (math.isinf(value) and not allow_inf):
        fail(doc, el, f"<{tag}> must be a finite number, got {text!r}")
    if positive and not value > 0:
        fail(doc, el, f"<{tag}> must be > 0, got {text!r}")
    if minimum is not None and value < minimum:
        fail(doc, el, f"<{tag}> must be >= {minimum:g}, got {text!r}")
    return value


def int_value(doc: Doc, parent: Element, tag: str, default: int, *, minimum: int | None = None) -> int:
    el = child(parent, tag)
    if el is None:
        return default
    text = (el.text or "").strip()
    value = c_int(text)
    if value is None:
        fail(doc, el, f"<{tag}> must be an integer, got {text!r}")
    if minimum is not None and value < minimum:
        fail(doc, el, f"<{tag}> must be >= {minimum}, got {text!r}")
    return value


_TRUE = ("true", "1")
_FALSE = ("false", "0")


def parse_bool(doc: Doc, el: Element, text: str) -> bool:
    t = text.strip().lower()
    if t in _TRUE:
        return True
    if t in _FALSE:
        return False
    fail(doc, el, f"<{el.tag}> must be true/false (or 1/0), got {text.strip()!r}")


def bool_value(doc: Doc, parent: Element, tag: str, default: bool) -> bool:
    el = child(parent, tag)
    if el is None or not (el.text or "").strip():
        return default
    return parse_bool(doc, el, el.text or "")


def vec3_value(doc: Doc, parent: Element, tag: str, default: tuple[float, float, float]) -> tuple[float, float, float]:
    el = child(parent, tag)
    if el is None:
        return default
    x, y, z = parse_floats(doc, el, 3)
    return (x, y, z)


def color_value(
    doc: Doc, parent: Element, tag: str, default: tuple[float, float, float, float] | None
) -> tuple[float, float, float, float] | None:
    el = child(parent, tag)
    if el is None:
        return default
    v = parse_floats(doc, el, (3, 4))
    return (v[0], v[1], v[2], v[3] if len(v) == 4 else 1.0)


MAX_POSITION_M = 1e7  # beyond this float64 poses lose millimetres; nothing real is that far away


def _check_position(doc: Doc, el: Element, xyz: tuple[float, ...]) -> None:
    if any(abs(c) > MAX_POSITION_M for c in xyz):
        fail(doc, el, f"<pose> position {xyz} is absurd", hint=f"coordinates are metres, within ±{MAX_POSITION_M:g}")


def parse_pose(doc: Doc, el: Element) -> tuple[Pose, str | None]:
    """A `<pose>` element: (pose, relative_to or None).

    Accepts `x y z roll pitch yaw` (radians, or degrees with degrees="true") and, with
    rotation_format="quat_xyzw", `x y z qx qy qz qw`. `<pose relative_to="f"/>` is the identity in frame f,
    as Gazebo's tutorials write it; a bare `<pose/>` says nothing and is refused.
    """
    relative_to = (el.get("relative_to") or "").strip() or None
    text = (el.text or "").strip()
    if not text:
        if relative_to is not None:
            return Pose(), relative_to
        fail(
            doc,
            el,
            "empty <pose/>",
            hint="write six numbers 'x y z roll pitch yaw' in metres and radians, or remove the element",
        )
    fmt = (el.get("rotation_format") or "euler_rpy").strip()
    if fmt == "quat_xyzw":
        v = parse_floats(doc, el, 7, "with rotation_format='quat_xyzw' needs")
        _check_position(doc, el, v[:3])
        try:
            q = quat_normalize(v[3:])
        except ValueError:
            fail(doc, el, f"<pose> quaternion {v[3:]} has zero length")
        return Pose((v[0], v[1], v[2]), q), relative_to
    if fmt != "euler_rpy":
        fail(doc, el, f"<pose> rotation_format {fmt!r} is not valid", hint="valid: 'euler_rpy', 'quat_xyzw'")
    v = parse_floats(doc, el, 6, "needs 'x y z roll pitch yaw':")
    _check_position(doc, el, v[:3])
    rpy = v[3:]
    degrees = el.get("degrees")
    if degrees is not None and parse_bool(doc, el, degrees):
        rpy = tuple(math.radians(a) for a in rpy)
    return Pose((v[0], v[1], v[2]), quat_from_rpy(*rpy)), relative_to


def pose_child(doc: Doc, parent: Element) -> tuple[Pose, str | None, Element | None]:
    """The `<pose>` child of `parent`: (pose, relative_to, element); identity when absent."""
    el = child(parent, "pose")
    if el is None:
        return Pose(), None, None
    pose, rel = parse_pose(doc, el)
    return pose, rel, el
