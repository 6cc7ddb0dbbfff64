"""`<gazebo>` extension tags of a URDF, read as sdformat's parser_urdf reads them.

`<gazebo>` without `reference` extends the model; `<gazebo reference="X">` the link or joint X. Known keys become
SDF elements (friction and contact on every collision of the link, material on its visuals, self_collide,
gravity, velocity_decay on the link, spring and stop parameters on the joint, `static` on the model); the
children of `<collision>`/`<visual>` wrappers go into every collision/visual of the link; anything else
(`<sensor>`, `<plugin>`, `<light>`, …) is copied verbatim.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field

from lxml import etree

from diffctl.description.pose import Pose
from diffctl.errors import DescriptionError

Element = etree._Element

# key → (SDF path under <collision>, numeric) — the friction and contact keys of parser_urdf.cc
COLLISION_KEYS = {
    "mu1": ("surface/friction/ode/mu", True),
    "mu2": ("surface/friction/ode/mu2", True),
    "fdir1": ("surface/friction/ode/fdir1", False),
    "kp": ("surface/contact/ode/kp", True),
    "kd": ("surface/contact/ode/kd", True),
    "maxVel": ("surface/contact/ode/max_vel", True),
    "minDepth": ("surface/contact/ode/min_depth", True),
    "maxContacts": ("max_contacts", True),
    "laserRetro": ("laser_retro", True),
}
LINK_KEYS = ("selfCollide", "turnGravityOff", "dampingFactor")
JOINT_KEYS = {
    "springReference": "axis/dynamics/spring_reference",
    "springStiffness": "axis/dynamics/spring_stiffness",
    "stopCfm": "physics/ode/cfm",
    "stopErp": "physics/ode/erp",
    "provideFeedback": "physics/provide_feedback",
    "implicitSpringDamper": "physics/ode/implicit_spring_damper",
    "fudgeFactor": "physics/ode/fudge_factor",
}
LUMPING_KEYS = ("preserveFixedJoint", "disableFixedJointLumping")
NUMERIC_KEYS = (
    *(k for k, (_, numeric) in COLLISION_KEYS.items() if numeric),
    "dampingFactor",
    "springReference",
    "springStiffness",
    "stopCfm",
    "stopErp",
    "fudgeFactor",
)
TRANSFORMED_BLOBS = ("sensor", "light", "projector")  # their poses follow a lumped link

# gazebo.material's colours for the Gazebo/* scripts gz-sim turns into colours (ambient = diffuse there).
GAZEBO_MATERIAL_RGBA: dict[str, tuple[float, float, float, float]] = {
    "Gazebo/Grey": (0.7, 0.7, 0.7, 1.0),
    "Gazebo/DarkGrey": (0.175, 0.175, 0.175, 1.0),
    "Gazebo/White": (1.0, 1.0, 1.0, 1.0),
    "Gazebo/FlatBlack": (0.1, 0.1, 0.1, 1.0),
    "Gazebo/Black": (0.0, 0.0, 0.0, 1.0),
    "Gazebo/Red": (1.0, 0.0, 0.0, 1.0),
    "Gazebo/RedBright": (0.87, 0.29, 0.19, 1.0),
    "Gazebo/Green": (0.0, 1.0, 0.0, 1.0),
    "Gazebo/Blue": (0.0, 0.0, 1.0, 1.0),
    "Gazebo/SkyBlue": (0.13, 0.44, 0.7, 1.0),
    "Gazebo/Yellow": (1.0, 1.0, 0.0, 1.0),
    "Gazebo/DarkYellow": (0.7, 0.7, 0.0, 1.0),
    "Gazebo/Purple": (1.0, 0.0, 1.0, 1.0),
    "Gazebo/Turquoise": (0.0, 1.0, 1.0, 1.0),
    "Gazebo/Orange": (1.0, 0.5088, 0.0468, 1.0),
}


@dataclass
class GazeboExtension:
    """One `<gazebo>` element. `origin_link` stays the link it was written for; `reference` follows lumping."""

    reference: str  # '' for the model
    line: int
    source: str
    values: dict[str, str] = field(default_factory=dict)  # known scalar keys, as written
    material: str = ""
    collision_blobs: list[Element] = field(default_factory=list)
    visual_blobs: list[Element] = field(default_factory=list)
    blobs: list[Element] = field(default_factory=list)
    origin_link: str = ""
    reduction: Pose = field(default_factory=Pose)  # the origin link's frame in the current reference link's frame

    def flag(self, key: str) -> bool | None:
        """A boolean key as parser_urdf reads it ('true', 'yes' or '1' is true), None when absent."""
        if key not in self.values:
            return None
        return self.values[key].strip().lower() in ("true", "yes", "1")

    def number(self, key: str) -> float | None:
        if key not in self.values:
            return None
        text = self.values[key]
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not math.isfinite(value):
            raise DescriptionError(
                f"<gazebo reference={self.reference!r}> <{key}> must be a finite number, got {text!r}",
                source=self.source,
                line=self.line,
                field=f"gazebo/{key}",
            )
        return value


def _value(el: Element) -> str:
    # parser_urdf accepts both <mu1>0.5</mu1> and <mu1 value="0.5"/>.
    return (el.get("value") if el.get("value") is not None else (el.text or "")).strip()


def read_extensions(elements: tuple[Element, ...], source: str) -> list[GazeboExtension]:
    out = []
    for g in elements:
        ref = (g.get("reference") or "").strip()
        ext = GazeboExtension(ref, g.sourceline or 0, source, origin_link=ref)
        for c in g:
            if not isinstance(c.tag, str):
                continue
            tag = str(c.tag)
            if tag == "material":
                ext.material = _value(c)
            elif tag in ("collision", "visual"):
                target = ext.collision_blobs if tag == "collision" else ext.visual_blobs
                target.extend(copy.deepcopy(k) for k in c if isinstance(k.tag, str))
            elif tag in COLLISION_KEYS or tag in LINK_KEYS or tag in JOINT_KEYS or tag in LUMPING_KEYS:
                ext.values[tag] = _value(c)
            elif tag == "static":
                ext.values["static"] = _value(c)
            else:
                ext.blobs.append(copy.deepcopy(c))
        for key in NUMERIC_KEYS:
            ext.number(key)  # a bad number stops the load here, naming the <gazebo> element
        out.append(ext)
    return out


def set_path(parent: Element, path: str, text: str, line: int) -> Element:
    """Create or overwrite the element at `path` (a/b/c) under `parent`, as parser_urdf's AddKeyValue does."""
    node = parent
    parts = path.split("/")
    for part in parts[:-1]:
        found = node.find(part)
        node = found if found is not None else etree.SubElement(node, part)
        node.sourceline = line
    old = node.find(parts[-1])
    if old is not None:
        node.remove(old)
    leaf = etree.SubElement(node, parts[-1])
    leaf.text = text
    leaf.sourceline = line
    return leaf


def apply_to_collision(ext: GazeboExtension, collision: Element) -> None:
    for blob in ext.collision_blobs:
        if blob.tag == "surface" and collision.find("surface") is not None:
            collision.remove(collision.find("surface"))
        collision.append(copy.deepcopy(blob))
    for key, (path, _) in COLLISION_KEYS.items():
        if key in ext.values:
            set_path(collision, path, ext.values[key], ext.line)


def _rgba_text(rgba: tuple[float, float, float, float]) -> str:
    return " ".join(f"{c:g}" for c in rgba)


def apply_to_visual(ext: GazeboExtension, visual: Element) -> None:
    for blob in ext.visual_blobs:
        if blob.tag == "material" and visual.find("material") is not None:
            visual.remove(visual.find("material"))
        visual.append(copy.deepcopy(blob))
    if ext.material:
        set_path(visual, "material/script/name", ext.material, ext.line)
        rgba = GAZEBO_MATERIAL_RGBA.get(ext.material)
        if rgba is not None:
            set_path(visual, "material/ambient", _rgba_text(rgba), ext.line)
            set_path(visual, "material/diffuse", _rgba_text(rgba), ext.line)


def apply_to_link(ext: GazeboExtension, link: Element, frame_of_origin: str | None) -> None:
    """Link keys and verbatim blobs; sensors, lights and projectors of a lumped link keep their place on it."""
    if ext.flag("selfCollide") is not None:
        set_path(link, "self_collide", "true" if ext.flag("selfCollide") else "false", ext.line)
    if ext.flag("turnGravityOff") is not None:
        set_path(link, "gravity", "false" if ext.flag("turnGravityOff") else "true", ext.line)
    damping = ext.number("dampingFactor")
    if damping is not None:
        set_path(link, "velocity_decay/linear", f"{damping:g}", ext.line)
    for blob in ext.blobs:
        item = copy.deepcopy(blob)
        if frame_of_origin is not None and item.tag in TRANSFORMED_BLOBS:
            pose = item.find("pose")
            if pose is None:
                pose = etree.SubElement(item, "pose")
                pose.text = "0 0 0 0 0 0"
                pose.sourceline = item.sourceline
            if pose.get("relative_to") is None:
                # The pose was written in the lumped link's frame, which survives as a model frame.
                pose.set("relative_to", frame_of_origin)
        link.append(item)


def apply_to_joint(ext: GazeboExtension, joint: Element) -> None:
    for key, path in JOINT_KEYS.items():
        if key in ext.values:
            if path.startswith("axis/") and joint.find("axis") is None:
                continue  # fixed joints have no axis to hold a spring
            set_path(joint, path, ext.values[key], ext.line)
    for blob in ext.blobs:
        joint.append(copy.deepcopy(blob))


def apply_to_model(ext: GazeboExtension, model: Element) -> None:
    if ext.flag("static") is not None:
        set_path(model, "static", "true" if ext.flag("static") else "false", ext.line)
    for blob in ext.blobs:
        model.append(copy.deepcopy(blob))
