"""The published state: free joint values (defaults, overwritten by source_list topics, or swept by
`delta`) and the dependent joints computed from them. Pure: no bus, no clock."""

from __future__ import annotations

import math
from dataclasses import dataclass

from diffctl.joint_state_publisher.joints import JointSet
from diffctl.joint_state_publisher.params import JspParams


@dataclass
class _Value:
    position: float | None
    velocity: float | None
    effort: float | None
    forward: bool = True


class JointStates:
    def __init__(self, joints: JointSet, params: JspParams) -> None:
        self.joints = joints
        self.values = {
            name: _Value(
                j.zero if params.publish_default_positions else None,
                0.0 if params.publish_default_velocities else None,
                0.0 if params.publish_default_efforts else None,
            )
            for name, j in joints.free.items()
        }

    def merge(self, names: list[str], positions: list[float], velocities: list[float], efforts: list[float]) -> None:
        """A source_list message: its values overwrite the free joints it names; others are ignored."""
        for i, name in enumerate(names):
            v = self.values.get(name)
            if v is None:
                continue
            for attr, seq in (("position", positions), ("velocity", velocities), ("effort", efforts)):
                if i < len(seq) and math.isfinite(seq[i]):
                    setattr(v, attr, float(seq[i]))

    def sweep(self, delta_rad: float) -> None:
        """Move every free joint by `delta_rad` per call, bouncing at limits (wrapping when continuous)."""
        for name, j in self.joints.free.items():
            v = self.values[name]
            if v.position is None:
                continue
            if v.forward:
                v.position += delta_rad
                if v.position > j.max_rad:
                    if j.continuous:
                        v.position = j.min_rad
                    else:
                        v.position, v.forward = j.max_rad, False
            else:
                v.position -= delta_rad
                if v.position < j.min_rad:
                    v.position, v.forward = j.min_rad, True

    def _follow(self, name: str) -> tuple[str, float, float]:
        """The free joint `name` depends on, with the combined factor and offset of the chain."""
        dep = self.joints.dependent[name]
        parent, factor, offset = dep.parent, dep.factor, dep.offset
        while parent in self.joints.dependent:
            up = self.joints.dependent[parent]
            offset += factor * up.offset
            factor *= up.factor
            parent = up.parent
        return parent, factor, offset

    def message(self) -> dict[str, list] | None:
        """name/position/velocity/effort lists in description order, or None when there is nothing to say."""
        if not self.joints.order:
            return None
        has = {
            attr: bool(self.joints.dependent and attr == "position")
            or any(getattr(v, attr) is not None for v in self.values.values())
            for attr in ("position", "velocity", "effort")
        }
        out: dict[str, list] = {"name": list(self.joints.order)}
        for attr in ("position", "velocity", "effort"):
            out[attr] = [0.0] * len(self.joints.order) if has[attr] else []
        for i, name in enumerate(self.joints.order):
            if name in self.values:
                source, factor, offset = name, 1.0, 0.0
            else:
                source, factor, offset = self._follow(name)
            v = self.values[source]
            if has["position"] and v.position is not None:
                out["position"][i] = v.position * factor + offset
            if has["velocity"] and v.velocity is not None:
                out["velocity"][i] = v.velocity * factor
            if has["effort"] and v.effort is not None:
                out["effort"][i] = v.effort
        return out
