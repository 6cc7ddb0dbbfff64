"""Each `<ros2_control>` joint's limits, from the robot description as ros2_control's component parser reads them.

A URDF joint's `<limit>` gives velocity and effort limits, and position limits on revolute and prismatic joints
(a continuous joint wraps around); `<safety_controller>` gives soft limits. An SDF description is read as
sdformat_urdf turns it into URDF: a revolute or prismatic `<axis><limit>` (unset values unbounded) is the
`<limit>`, a continuous joint has none. Then the joint's command interfaces narrow them: a `min`/`max` on position,
velocity or effort takes the tighter of the two (velocity and effort bounds are symmetric, the smaller magnitude),
on acceleration they are the deceleration and acceleration limits, on jerk the max is. `<limits enable="false"/>`
in an interface keeps its group off; in the joint, the joint gets no limiter at all.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

from lxml import etree

from diffctl.control.hardware_interface import ComponentInfo, HardwareInfo
from diffctl.control.joint_limits.joint_limits import _DBL_MAX, JointLimits, SoftJointLimits
from diffctl.control.joint_limits.joint_limits_helpers import cmax, cmin
from diffctl.description.urdf.parse import UrdfLimit, UrdfSafety, parse_root, parse_urdf
from diffctl.errors import DescriptionError

_INF = math.inf


class DescribedJoint(NamedTuple):
    """What the limits need of a description's joint: its URDF type, `<limit>` and `<safety_controller>`."""

    type: str
    limit: UrdfLimit | None
    safety: UrdfSafety | None


@dataclass(frozen=True)
class JointLimiterSpec:
    """A joint of a `<ros2_control>` block that gets a limiter: soft limits make it a soft limiter."""

    hardware: str
    joint: str
    limits: JointLimits
    soft_limits: SoftJointLimits | None


def get_joint_limits(joint: DescribedJoint) -> JointLimits:
    """The limits of a joint's `<limit>` (none set without one)."""
    limits = JointLimits()
    if joint.limit is None:
        return limits
    limits.has_position_limits = joint.type in ("revolute", "prismatic")
    if limits.has_position_limits:
        limits.min_position, limits.max_position = joint.limit.lower, joint.limit.upper
    elif joint.type == "continuous":
        limits.angle_wraparound = True
    limits.has_velocity_limits = True
    limits.max_velocity = abs(joint.limit.velocity)
    limits.has_effort_limits = True
    limits.max_effort = abs(joint.limit.effort)
    return limits


def get_soft_joint_limits(joint: DescribedJoint) -> SoftJointLimits | None:
    s = joint.safety
    if s is None:
        return None
    return SoftJointLimits(s.soft_lower_limit, s.soft_upper_limit, s.k_position, s.k_velocity)


def _given(minimum: float, maximum: float) -> bool:
    # an absent min/max is -inf/inf in InterfaceInfo
    return minimum != -_INF or maximum != _INF


def update_interface_limits(joint: ComponentInfo, limits: JointLimits) -> list[str]:
    """Narrow `limits` (in place) by the joint's command interfaces' min/max; the warnings ros2_control prints
    for min/max it can not use."""
    warnings: list[str] = []
    if not joint.enable_limits:
        limits.disable_all_limits()
        return warnings
    for it in joint.command_interfaces:
        on, given = it.enable_limits, _given(it.min, it.max)
        if it.name == "position":
            if not (limits.has_position_limits and on):
                limits.min_position, limits.max_position = -_DBL_MAX, _DBL_MAX
            if on and given:
                limits.min_position = cmax(it.min, limits.min_position)
                limits.max_position = cmin(it.max, limits.max_position)
                limits.has_position_limits = True
            limits.has_position_limits = limits.has_position_limits and on
        elif it.name in ("velocity", "effort"):
            attr, flag = f"max_{it.name}", f"has_{it.name}_limits"
            if not getattr(limits, flag):
                setattr(limits, attr, _DBL_MAX)
            if on and given:
                # symmetric: the smaller of |min| and max, and never looser than the URDF's
                setattr(limits, attr, cmin(cmin(abs(it.min), it.max), getattr(limits, attr)))
                setattr(limits, flag, True)
            setattr(limits, flag, getattr(limits, flag) and on)
        elif it.name == "acceleration":
            if given:
                if math.isfinite(it.min):
                    limits.max_deceleration = abs(it.min)
                    if not math.isfinite(it.max):
                        limits.max_acceleration = limits.max_deceleration
                    limits.has_deceleration_limits = on
                if math.isfinite(it.max):
                    limits.max_acceleration = it.max
                    if not math.isfinite(limits.max_deceleration):
                        limits.max_deceleration = abs(limits.max_acceleration)
                    limits.has_acceleration_limits = on
        elif it.name == "jerk":
            if it.min != -_INF:
                warnings.append(
                    "Error parsing the limits for the interface: jerk from the tag: min within ros2_control tag "
                    "inside the URDF. Jerk only accepts max limits."
                )
            if it.max != _INF and math.isfinite(it.max):
                limits.max_jerk = abs(it.max)
                limits.has_jerk_limits = on
        elif given:
            warnings.append(
                f"Unable to parse the limits for the interface: {it.name} from the tags [min and max] within "
                "ros2_control tag inside the URDF. Supported interfaces for joint limits are: position, velocity, "
                "effort, acceleration and jerk."
            )
    return warnings


def _sdf_number(el: etree._Element, tag: str, default: float, source: str) -> float:
    text = el.findtext(tag)
    if text is None or not text.strip():
        return default
    try:
        return float(text)
    except ValueError:
        raise DescriptionError(f"<{tag}> must be a number, got {text.strip()!r}", source=source,
                               line=el.sourceline, field=f"joint/axis/limit/{tag}") from None


def _sdf_joints(root: etree._Element, source: str) -> dict[str, DescribedJoint]:
    out: dict[str, DescribedJoint] = {}
    for el in root.iter("joint"):
        parent = el.getparent()
        if parent is None or parent.tag != "model":
            continue  # a <ros2_control> block's <joint>
        kind = (el.get("type") or "").strip()
        limit = None
        if kind in ("revolute", "prismatic"):
            lim = el.find("axis/limit")
            if lim is None:
                limit = UrdfLimit(-_INF, _INF, _INF, _INF)
            else:
                limit = UrdfLimit(_sdf_number(lim, "lower", -_INF, source), _sdf_number(lim, "upper", _INF, source),
                                  _sdf_number(lim, "effort", _INF, source), _sdf_number(lim, "velocity", _INF, source))
        out[(el.get("name") or "").strip()] = DescribedJoint(kind, limit, None)
    return out


def description_joints(description: str, source: str) -> dict[str, DescribedJoint]:
    """The joints of a URDF (validated as urdfdom does) or SDF robot description, by name."""
    root = parse_root(description, source)
    if root.tag == "sdf":
        return _sdf_joints(root, source)
    robot = parse_urdf(root, source)
    return {name: DescribedJoint(j.type, j.limit, j.safety) for name, j in robot.joints.items()}


def hardware_joint_limits(
    infos: list[HardwareInfo] | tuple[HardwareInfo, ...], description: str, source: str = "robot_description"
) -> tuple[list[JointLimiterSpec], list[tuple[str, str]]]:
    """(the limiters to make, (level, message) to log) for every joint of every block; an empty description gives
    the interfaces' limits alone. A block's joint the description lacks is a DescriptionError."""
    joints = description_joints(description, source) if description.strip() else None
    specs: list[JointLimiterSpec] = []
    notes: list[tuple[str, str]] = []
    for info in infos:
        for joint in info.joints:
            described = DescribedJoint("", None, None)
            if joints is not None:
                found = joints.get(joint.name)
                if found is None:
                    raise DescriptionError(f"Joint '{joint.name}' not found in URDF", source=info.source or source,
                                           field=f"ros2_control[{info.name}]/joint[{joint.name}]",
                                           hint="name a joint of the robot description")
                described = found
            limits = get_joint_limits(described)
            notes += [("warn", w) for w in update_interface_limits(joint, limits)]
            soft = get_soft_joint_limits(described)
            if soft is not None and limits.has_position_limits:
                soft.min_position = cmax(soft.min_position, limits.min_position)
                soft.max_position = cmin(soft.max_position, limits.max_position)
            if not joint.enable_limits:
                notes.append(("info", f"Joint limits are disabled for joint '{joint.name}' in hardware '{info.name}'"))
                continue
            specs.append(JointLimiterSpec(info.name, joint.name, limits, soft))
    return specs, notes
