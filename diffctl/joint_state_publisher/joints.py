"""The free and dependent joints of a URDF or SDF description, as joint_state_publisher reads them.

URDF: every joint but fixed, floating and planar; continuous joints range over ±π, the others need
`<limit lower upper>`, narrowed by `<safety_controller soft_*_limit>` when asked; `<mimic>` makes a joint
dependent. SDF (first model): every joint but fixed, ball, gearbox, revolute2, screw and universal; an
SDF revolute joint without `<limit>` is unlimited in SDF, so it is taken as continuous. The default
position is `zeros.<joint>`, else 0 when within the limits, else the middle of the range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from lxml import etree

from diffctl.errors import DescriptionError, xml_error
from diffctl.joint_state_publisher.params import Dependent, JspParams

URDF_SKIPPED = ("fixed", "floating", "planar")
SDF_SKIPPED = ("fixed", "ball", "gearbox", "revolute2", "screw", "universal")


@dataclass(frozen=True)
class FreeJoint:
    name: str
    min_rad: float
    max_rad: float
    zero: float
    continuous: bool = False


@dataclass(frozen=True)
class JointSet:
    order: tuple[str, ...]  # every published joint, in the description's order
    free: dict[str, FreeJoint] = field(default_factory=dict)
    dependent: dict[str, Dependent] = field(default_factory=dict)


def _float(el: etree._Element, joint: str, what: str, text: str | None, source: str) -> float:
    try:
        value = float(text if text is not None else "")
    except ValueError:
        raise DescriptionError(
            f'"{what}" limit of joint {joint!r} must be a number, got {text!r}', source=source, line=el.sourceline
        ) from None
    if not math.isfinite(value):
        raise DescriptionError(f'"{what}" limit of joint {joint!r} is {value}', source=source, line=el.sourceline)
    return value


def _zero(params: JspParams, name: str, lo: float, hi: float) -> float:
    if name in params.zeros:
        return params.zeros[name]
    return (lo + hi) / 2 if lo > 0 or hi < 0 else 0.0


def _urdf(root: etree._Element, params: JspParams, source: str) -> JointSet:
    order: list[str] = []
    free: dict[str, FreeJoint] = {}
    dependent: dict[str, Dependent] = dict(params.dependent_joints)
    for j in root.findall("joint"):
        jtype, name = j.get("type", ""), j.get("name", "")
        if jtype in URDF_SKIPPED:
            continue
        if jtype == "continuous":
            lo, hi = -math.pi, math.pi
        else:
            limit = j.find("limit")
            if limit is None:
                raise DescriptionError(
                    f"joint {name!r} of type {jtype!r} has no <limit>", source=source, line=j.sourceline
                )
            for attr in ("lower", "upper"):
                if limit.get(attr) is None:
                    raise DescriptionError(
                        f'joint {name!r} of type {jtype!r} has no "{attr}" limit', source=source, line=limit.sourceline
                    )
            lo = _float(limit, name, "lower", limit.get("lower"), source)
            hi = _float(limit, name, "upper", limit.get("upper"), source)
        safety = j.findall("safety_controller")
        if params.use_smallest_joint_limits and len(safety) == 1:
            s = safety[0]
            if s.get("soft_lower_limit") is not None:
                lo = max(lo, _float(s, name, "soft_lower_limit", s.get("soft_lower_limit"), source))
            if s.get("soft_upper_limit") is not None:
                hi = min(hi, _float(s, name, "soft_upper_limit", s.get("soft_upper_limit"), source))
        order.append(name)
        mimic = j.findall("mimic")
        if params.use_mimic_tags and len(mimic) == 1:
            m = mimic[0]
            dependent[name] = Dependent(
                m.get("joint", ""),
                _float(m, name, "multiplier", m.get("multiplier", "1"), source),
                _float(m, name, "offset", m.get("offset", "0"), source),
            )
            continue
        if name in dependent:
            continue
        free[name] = FreeJoint(name, lo, hi, _zero(params, name, lo, hi), jtype == "continuous")
    return JointSet(tuple(order), free, {k: v for k, v in dependent.items() if k in order})


def _sdf(root: etree._Element, params: JspParams, source: str) -> JointSet:
    model = root.find(".//model")
    if model is None:
        raise DescriptionError("the SDF has no <model>", source=source, line=root.sourceline)
    order: list[str] = []
    free: dict[str, FreeJoint] = {}
    for j in model.findall("joint"):
        jtype, name = j.get("type", ""), j.get("name", "")
        if jtype in SDF_SKIPPED:
            continue
        limit = j.find("axis/limit")
        lower = limit.findtext("lower") if limit is not None else None
        upper = limit.findtext("upper") if limit is not None else None
        continuous = jtype == "continuous" or (jtype == "revolute" and (lower is None or upper is None))
        if continuous:
            lo, hi = -math.pi, math.pi
        else:
            if limit is None or lower is None or upper is None:
                raise DescriptionError(
                    f"joint {name!r} of type {jtype!r} has no <axis><limit><lower>/<upper>",
                    source=source,
                    line=j.sourceline,
                )
            lo = _float(limit, name, "lower", lower, source)
            hi = _float(limit, name, "upper", upper, source)
            # SDF writes "unlimited" as ±1e16: sweep and midpoint would be meaningless there.
            if lo < -1e15 and hi > 1e15:
                lo, hi, continuous = -math.pi, math.pi, jtype == "revolute"
        order.append(name)
        if name in params.dependent_joints:
            continue
        free[name] = FreeJoint(name, lo, hi, _zero(params, name, lo, hi), continuous)
    dependent = {k: v for k, v in params.dependent_joints.items() if k in order}
    return JointSet(tuple(order), free, dependent)


def parse_joints(description: str, params: JspParams, source: str = "robot_description") -> JointSet:
    """The joints to publish; a description that cannot be used is one DescriptionError."""
    try:
        root = etree.fromstring(
            description.encode(), etree.XMLParser(remove_comments=True, resolve_entities=False, no_network=True)
        )
    except etree.XMLSyntaxError as e:
        raise xml_error(e, source) from None
    tag = etree.QName(root).localname
    if tag == "sdf":
        joints = _sdf(root, params, source)
    elif tag == "robot":
        joints = _urdf(root, params, source)
    else:
        raise DescriptionError(f"root element <{tag}> is neither <robot> (URDF) nor <sdf>", source=source)
    check_chains(joints, source)
    return joints


def check_chains(joints: JointSet, source: str) -> None:
    """Every dependent joint must lead to a free joint without a cycle."""
    for name in joints.dependent:
        seen = [name]
        parent = joints.dependent[name].parent
        while parent in joints.dependent:
            if parent in seen:
                raise DescriptionError(f"mimic joints form a cycle: {' -> '.join([*seen, parent])}", source=source)
            seen.append(parent)
            parent = joints.dependent[parent].parent
        if parent not in joints.free:
            raise DescriptionError(
                f"joint {seen[-1]!r} mimics {parent!r}, which is not a free joint of the description", source=source
            )
