"""`<ros2_control>` blocks and the gz_ros2_control plugin's parameter files, read from SDF or URDF text.

These work on the raw XML, without resolving frames or meshes, so the controller manager can read them from a
`robot_description` string whose mesh paths belong to another machine.
"""

from __future__ import annotations

import math
from pathlib import Path

from lxml import etree

from diffctl.description.model import Model, Ros2Control, Ros2ControlInterface, Ros2ControlJoint
from diffctl.errors import DescriptionError, xml_error

HARDWARE_TYPES = ("system", "actuator", "sensor")
# hardware_interface::HandleDataType (ros2_control 4.46): a handle of any other type fails to construct
DATA_TYPES = ("double", "bool", "float32", "uint8", "int8", "uint16", "int16", "uint32", "int32")
GZ_ROS2_CONTROL_FILENAMES = ("gz_ros2_control-system", "libgz_ros2_control-system", "ign_ros2_control-system")


def _fail(el: etree._Element, source: str, message: str, hint: str | None = None) -> None:
    raise DescriptionError(message, source=source, line=el.sourceline, field=f"ros2_control/{el.tag}", hint=hint)


def _params(el: etree._Element, source: str, skip: tuple[str, ...] = ()) -> tuple[tuple[str, str], ...]:
    out = []
    for p in el.findall("param"):
        name = (p.get("name") or "").strip()
        if not name:
            _fail(p, source, "<param> needs a name attribute")
        if name not in skip:
            out.append((name, (p.text or "").strip()))
    return tuple(out)


def _number(el: etree._Element, source: str, name: str, text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        _fail(el, source, f"parameter {name!r} must be a number, got {text!r}")
    if math.isnan(value):
        _fail(el, source, f"parameter {name!r} must not be NaN")
    return value


def _enable_limits(el: etree._Element, source: str) -> bool:
    """A `<limits enable="true|false"/>` child (any letter case, as ros2_control's parse_bool); true without one."""
    limits = el.find("limits")
    if limits is None:
        return True
    text = limits.get("enable")
    if text is None:
        _fail(limits, source, "no attribute 'enable' in 'limits' tag", 'e.g. <limits enable="false"/>')
    value = text.strip().lower()
    if value not in ("true", "false"):
        _fail(limits, source, f"Input string : {text.strip()!r} is not a valid boolean value. Expected 'true' or "
              f"'false'.")
    return value == "true"


def _interface(el: etree._Element, source: str) -> Ros2ControlInterface:
    name = (el.get("name") or "").strip()
    if not name:
        _fail(el, source, f"<{el.tag}> needs a name attribute", 'e.g. name="velocity"')
    data_type = (el.get("data_type") or "double").strip()
    if data_type not in DATA_TYPES:
        _fail(
            el,
            source,
            f"<{el.tag} name={name!r}> has data_type {data_type!r}",
            f"one of {', '.join(DATA_TYPES)} (double when absent)",
        )
    values: dict[str, float | None] = {"initial_value": None, "min": None, "max": None}
    for p in el.findall("param"):
        pname = (p.get("name") or "").strip()
        if pname in values:
            text = (p.text or "").strip()
            if data_type == "bool" and text.lower() in ("true", "false"):
                text = "1" if text.lower() == "true" else "0"  # a bool handle's initial_value is true/false
            values[pname] = _number(p, source, pname, text)
    return Ros2ControlInterface(
        name,
        values["initial_value"],
        _params(el, source, skip=tuple(values)),
        values["min"],
        values["max"],
        data_type,
        _enable_limits(el, source),
    )


def _component(el: etree._Element, source: str, with_commands: bool) -> Ros2ControlJoint:
    name = (el.get("name") or "").strip()
    if not name:
        _fail(el, source, f"<{el.tag}> in <ros2_control> needs a name attribute")
    commands = tuple(_interface(c, source) for c in el.findall("command_interface")) if with_commands else ()
    states = tuple(_interface(c, source) for c in el.findall("state_interface"))
    for group, kind in ((commands, "command"), (states, "state")):
        names = [i.name for i in group]
        for n in names:
            if names.count(n) > 1:
                _fail(el, source, f"{el.tag} {name!r} declares {kind} interface {n!r} twice")
    return Ros2ControlJoint(name, commands, states, _params(el, source), _enable_limits(el, source))


def parse_ros2_control(block: etree._Element | str, source: str = "<string>") -> Ros2Control:
    """One `<ros2_control name=… type=…>` element (or its XML text) as a Ros2Control."""
    if isinstance(block, str):
        try:
            block = etree.fromstring(block.encode())
        except etree.XMLSyntaxError as e:
            raise xml_error(e, source) from None
    if block.tag != "ros2_control":
        _fail(block, source, f"expected a <ros2_control> element, got <{block.tag}>")
    name = (block.get("name") or "").strip()
    if not name:
        _fail(block, source, "<ros2_control> needs a name attribute")
    kind = (block.get("type") or "").strip().lower()
    if kind not in HARDWARE_TYPES:
        _fail(
            block,
            source,
            f"<ros2_control name={name!r}> type {block.get('type')!r} is not valid",
            "valid: " + ", ".join(HARDWARE_TYPES),
        )
    hardware = block.find("hardware")
    # ros2_control's component parser: a block without <hardware> parses (its plugin name empty, which only
    # loading it refuses: gz_ros2_control skips it, robot_state_publisher never looks); <hardware> without a
    # <plugin> does not
    plugin = ""
    if hardware is not None:
        plugin = (hardware.findtext("plugin") or "").strip()
        if hardware.find("plugin") is None:
            _fail(
                hardware,
                source,
                f"Missing <plugin> tag of <hardware> element for '{name}' in your URDF.",
                "e.g. <plugin>gz_ros2_control/GazeboSimSystem</plugin> or mock_components/GenericSystem",
            )
    joints = tuple(_component(j, source, True) for j in block.findall("joint"))
    seen: set[str] = set()
    for j in joints:
        if j.name in seen:
            _fail(block, source, f"joint {j.name!r} appears twice in <ros2_control name={name!r}>")
        seen.add(j.name)
    return Ros2Control(
        name=name,
        type=kind,
        hardware_plugin=plugin,
        hardware_params=_params(hardware, source) if hardware is not None else (),
        joints=joints,
        sensors=tuple(_component(s, source, False) for s in block.findall("sensor")),
        gpios=tuple(_component(g, source, True) for g in block.findall("gpio")),
    )


def _root(description: str, source: str) -> etree._Element:
    try:
        return etree.fromstring(description.encode())
    except etree.XMLSyntaxError as e:
        raise xml_error(e, source) from None


def ros2_control_blocks(description: str, source: str = "robot_description") -> list[Ros2Control]:
    """Every `<ros2_control>` block of an SDF or URDF robot description, in document order."""
    return [parse_ros2_control(el, source) for el in _root(description, source).iter("ros2_control")]


def _is_gz_ros2_control(filename: str) -> bool:
    base = Path(filename).name.removesuffix(".so")
    return base in GZ_ROS2_CONTROL_FILENAMES


def gz_ros2_control_parameters(description: str | Model, source: str = "robot_description") -> list[str]:
    """The `<parameters>` files of the gz_ros2_control plugin (repeatable; empty list when there is no plugin).

    An empty `<parameters/>` is refused, as gz_ros2_control does ("found an empty parameters file").
    """
    if isinstance(description, Model):
        out: list[str] = []
        for p in description.plugins:
            if _is_gz_ros2_control(p.filename):
                for value in p.get_all("parameters"):
                    if not value:
                        raise DescriptionError(
                            "gz_ros2_control plugin has an empty <parameters>", source=description.source
                        )
                    out.append(value)
        return out
    out = []
    for plugin in _root(description, source).iter("plugin"):
        if _is_gz_ros2_control(plugin.get("filename") or ""):
            for el in plugin.findall("parameters"):
                value = (el.text or "").strip()
                if not value:
                    _fail(
                        el,
                        source,
                        "gz_ros2_control plugin has an empty <parameters>",
                        "give the path of the controller manager's YAML file",
                    )
                out.append(value)
    return out
