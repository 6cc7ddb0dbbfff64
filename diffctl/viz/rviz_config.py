"""RViz2 `.rviz` files: the fixed frame and the displays (with their topics) the visualizer should show.

An `.rviz` file is YAML; what matters here is `Visualization Manager: {Global Options: {Fixed Frame},
Displays: [{Class, Name, Enabled, Topic…}]}`. RViz2 writes a topic either as a string or as a mapping
with its QoS and a `Value`; both are read. Display classes we cannot draw are listed once as ignored.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from diffctl.errors import ConfigError, yaml_error

# RViz2 display class → what the page draws, and the key that holds the display's topic.
DISPLAY_KINDS: dict[str, tuple[str, str | None]] = {
    "rviz_default_plugins/Grid": ("grid", None),
    "rviz_default_plugins/RobotModel": ("robot_model", "Description Topic"),
    "rviz_default_plugins/TF": ("tf", None),
    "rviz_default_plugins/Odometry": ("odometry", "Topic"),
    "rviz_default_plugins/LaserScan": ("laser_scan", "Topic"),
    "rviz_default_plugins/Image": ("image", "Topic"),
    "rviz_default_plugins/Camera": ("image", "Topic"),
}
GROUP_CLASS = "rviz_common/Group"

DEFAULT_TOPICS = {
    "robot_model": "/robot_description",
    "odometry": "/diffbot_base_controller/odom",
    "laser_scan": "/scan",
    "image": "/camera/image_raw",
}
DEFAULT_COLORS = {"grid": (160, 160, 164), "odometry": (255, 25, 0), "laser_scan": (255, 0, 0)}


def hex_color(rgb: tuple[int, int, int]) -> str:
    return "#" + "".join(f"{c:02x}" for c in rgb)


@dataclass(frozen=True)
class Display:
    """One display of the page: `kind` in grid, robot_model, tf, odometry, laser_scan, image."""

    kind: str
    name: str
    enabled: bool = True
    topic: str | None = None
    color_rgb: tuple[int, int, int] | None = None
    rviz_class: str = ""
    keep: int = 100  # Odometry: how many poses the trail keeps
    cell_size_m: float = 1.0  # Grid
    cell_count: int = 10  # Grid
    point_size_m: float = 0.05  # LaserScan
    marker_scale: float = 1.0  # TF: axes are 0.1 m times this, as in RViz
    show_names: bool = True  # TF
    tf_prefix: str = ""  # RobotModel: its links are the frames "<prefix>/<link>" (a namespaced robot's TF)

    def to_json(self) -> dict[str, Any]:
        return {
            "kind": self.kind,
            "name": self.name,
            "enabled": self.enabled,
            "topic": self.topic,
            "color": hex_color(self.color_rgb) if self.color_rgb else None,
            "class": self.rviz_class,
            "keep": self.keep,
            "cell_size": self.cell_size_m,
            "cell_count": self.cell_count,
            "point_size": self.point_size_m,
            "marker_scale": self.marker_scale,
            "show_names": self.show_names,
            "tf_prefix": self.tf_prefix,
        }


@dataclass(frozen=True)
class RvizConfig:
    fixed_frame: str = "odom"
    displays: tuple[Display, ...] = ()
    background_rgb: tuple[int, int, int] = (48, 48, 48)
    frame_rate_hz: float = 30.0
    ignored: tuple[str, ...] = ()  # display classes we do not draw, each listed once
    source: str | None = None

    def topics(self, kind: str, *, enabled_only: bool = True) -> list[str]:
        """Topics of the displays of one kind, each once, in file order."""
        return list(
            dict.fromkeys(
                d.topic for d in self.displays if d.kind == kind and d.topic and (d.enabled or not enabled_only)
            )
        )

    def robot_models(self) -> list[tuple[str, str]]:
        """(description topic, TF prefix) of every RobotModel display, each pair once, in file order."""
        return list(dict.fromkeys((d.topic, d.tf_prefix) for d in self.displays if d.kind == "robot_model" and d.topic))

    def to_json(self) -> dict[str, Any]:
        return {
            "fixed_frame": self.fixed_frame,
            "background": hex_color(self.background_rgb),
            "displays": [d.to_json() for d in self.displays],
            "ignored": list(self.ignored),
            "source": self.source,
        }


def default_config() -> RvizConfig:
    """What the page shows without `-d`: the car's usual set, as config/diffbot.rviz has it."""
    return RvizConfig(
        fixed_frame="odom",
        displays=(
            Display("grid", "Grid", color_rgb=DEFAULT_COLORS["grid"], rviz_class="rviz_default_plugins/Grid"),
            Display(
                "robot_model",
                "RobotModel",
                topic=DEFAULT_TOPICS["robot_model"],
                rviz_class="rviz_default_plugins/RobotModel",
            ),
            Display("tf", "TF", rviz_class="rviz_default_plugins/TF"),
            Display(
                "odometry",
                "Odometry",
                topic=DEFAULT_TOPICS["odometry"],
                color_rgb=DEFAULT_COLORS["odometry"],
                rviz_class="rviz_default_plugins/Odometry",
            ),
            # The earlier tutorial variant: Gazebo's DiffDrive odometry bridged to /odom.
            Display(
                "odometry",
                "Odometry (bridged)",
                topic="/odom",
                color_rgb=(255, 170, 0),
                rviz_class="rviz_default_plugins/Odometry",
            ),
            Display(
                "laser_scan",
                "LaserScan",
                topic=DEFAULT_TOPICS["laser_scan"],
                color_rgb=DEFAULT_COLORS["laser_scan"],
                rviz_class="rviz_default_plugins/LaserScan",
            ),
            Display("image", "Image", topic=DEFAULT_TOPICS["image"], rviz_class="rviz_default_plugins/Image"),
        ),
    )


class _Reader:
    """Field access on the parsed YAML with errors that name the file and the field path."""

    def __init__(self, source: str) -> None:
        self.source = source

    def fail(self, field_path: str, message: str) -> ConfigError:
        return ConfigError(message, source=self.source, field=field_path)

    def mapping(self, value: Any, field_path: str) -> dict[str, Any]:
        if value is None:
            return {}
        if not isinstance(value, dict):
            raise self.fail(field_path, f"must be a mapping, got {type(value).__name__} {value!r}")
        return value

    def text(self, value: Any, field_path: str) -> str:
        if not isinstance(value, str | int | float) or isinstance(value, bool):
            raise self.fail(field_path, f"must be a string, got {value!r}")
        return str(value)

    def boolean(self, value: Any, field_path: str) -> bool:
        if not isinstance(value, bool):
            raise self.fail(field_path, f"must be true or false, got {value!r}")
        return value

    def number(self, value: Any, field_path: str, *, low: float, high: float) -> float:
        if isinstance(value, bool) or not isinstance(value, int | float) or not (low <= float(value) <= high):
            raise self.fail(field_path, f"must be a number in [{low:g}, {high:g}], got {value!r}")
        return float(value)

    def color(self, value: Any, field_path: str) -> tuple[int, int, int]:
        # RViz writes colours as "R; G; B" with 0–255 components.
        parts = [p.strip() for p in str(value).split(";")]
        try:
            rgb = tuple(int(float(p)) for p in parts)
        except ValueError:
            rgb = ()
        if len(rgb) != 3 or not all(0 <= c <= 255 for c in rgb):
            raise self.fail(field_path, f"must be a colour 'R; G; B' with components 0–255, got {value!r}")
        return rgb  # type: ignore[return-value]

    def topic(self, value: Any, field_path: str) -> str | None:
        if isinstance(value, dict):
            value = value.get("Value")
            field_path += ".Value"
        if value is None or value == "":
            return None
        name = self.text(value, field_path).strip()
        if not name.startswith("/"):
            name = "/" + name  # RViz resolves relative names in the global namespace
        if any(c.isspace() for c in name) or "//" in name:
            raise self.fail(field_path, f"is not a valid topic name: {value!r}")
        return name


def _display(r: _Reader, item: Any, path: str, ignored: list[str]) -> list[Display]:
    d = r.mapping(item, path)
    if "Class" not in d:
        raise r.fail(path, "display has no 'Class' (e.g. rviz_default_plugins/LaserScan)")
    cls = r.text(d["Class"], path + ".Class")
    name = r.text(d.get("Name", cls.split("/")[-1]), path + ".Name")
    enabled = r.boolean(d.get("Enabled", True), path + ".Enabled")
    if cls == GROUP_CLASS:
        children = d.get("Displays") or []
        if not isinstance(children, list):
            raise r.fail(path + ".Displays", "must be a list of displays")
        out: list[Display] = []
        for i, child in enumerate(children):
            for sub in _display(r, child, f"{path}.Displays[{i}]", ignored):
                out.append(Display(**{**sub.__dict__, "enabled": sub.enabled and enabled}))
        return out
    if cls not in DISPLAY_KINDS:
        if cls not in ignored:
            ignored.append(cls)
        return []
    kind, topic_key = DISPLAY_KINDS[cls]
    topic = DEFAULT_TOPICS.get(kind) if topic_key else None
    if topic_key and topic_key in d:
        topic = r.topic(d[topic_key], f"{path}.{topic_key}")
    if kind == "robot_model" and str(d.get("Description Source", "Topic")) not in ("Topic",):
        raise r.fail(path + ".Description Source", f"only 'Topic' is supported, got {d['Description Source']!r}")
    color = DEFAULT_COLORS.get(kind)
    if "Color" in d:
        color = r.color(d["Color"], path + ".Color")
    elif kind == "odometry" and isinstance(d.get("Shape"), dict) and "Color" in d["Shape"]:
        color = r.color(d["Shape"]["Color"], path + ".Shape.Color")
    kw: dict[str, Any] = {}
    if kind == "odometry" and "Keep" in d:
        kw["keep"] = int(r.number(d["Keep"], path + ".Keep", low=0, high=100_000))
    if kind == "grid":
        if "Cell Size" in d:
            kw["cell_size_m"] = r.number(d["Cell Size"], path + ".Cell Size", low=1e-3, high=1e3)
        if "Plane Cell Count" in d:
            kw["cell_count"] = int(r.number(d["Plane Cell Count"], path + ".Plane Cell Count", low=1, high=1000))
    if kind == "tf":
        if "Marker Scale" in d:
            kw["marker_scale"] = r.number(d["Marker Scale"], path + ".Marker Scale", low=1e-3, high=100)
        if "Show Names" in d:
            kw["show_names"] = r.boolean(d["Show Names"], path + ".Show Names")
    if kind == "robot_model" and d.get("TF Prefix"):
        prefix = r.text(d["TF Prefix"], path + ".TF Prefix").strip().strip("/")
        if any(c.isspace() for c in prefix) or "//" in prefix:
            raise r.fail(path + ".TF Prefix", f"must be a frame prefix such as robot1, got {d['TF Prefix']!r}")
        kw["tf_prefix"] = prefix
    if kind == "laser_scan" and "Size (m)" in d:
        kw["point_size_m"] = r.number(d["Size (m)"], path + ".Size (m)", low=1e-4, high=10)
    return [Display(kind, name, enabled, topic, color, cls, **kw)]


def parse_rviz(text: str, source: str = "<rviz>") -> RvizConfig:
    r = _Reader(source)
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as e:
        raise yaml_error(e, source, "malformed RViz config") from None
    top = r.mapping(data, "(top level)")
    if "Visualization Manager" not in top:
        raise r.fail("(top level)", "not an RViz config: no 'Visualization Manager' section")
    vm = r.mapping(top["Visualization Manager"], "Visualization Manager")
    glob = r.mapping(vm.get("Global Options"), "Visualization Manager.Global Options")
    gpath = "Visualization Manager.Global Options"
    fixed = r.text(glob.get("Fixed Frame", "odom"), gpath + ".Fixed Frame").strip().lstrip("/")
    if not fixed or any(c.isspace() for c in fixed):
        raise r.fail(gpath + ".Fixed Frame", f"must be a frame name, got {glob.get('Fixed Frame')!r}")
    background = (
        r.color(glob["Background Color"], gpath + ".Background Color") if "Background Color" in glob else (48, 48, 48)
    )
    rate = r.number(glob.get("Frame Rate", 30), gpath + ".Frame Rate", low=1, high=60)
    items = vm.get("Displays") or []
    if not isinstance(items, list):
        raise r.fail("Visualization Manager.Displays", "must be a list of displays")
    ignored: list[str] = []
    displays: list[Display] = []
    for i, item in enumerate(items):
        displays += _display(r, item, f"Visualization Manager.Displays[{i}]", ignored)
    return RvizConfig(fixed, tuple(displays), background, rate, tuple(ignored), source)


def load_rviz(path: str | Path) -> RvizConfig:
    p = Path(path)
    try:
        text = p.read_text()
    except FileNotFoundError:
        raise ConfigError("RViz config file not found", source=str(p)) from None
    except (IsADirectoryError, PermissionError, UnicodeDecodeError) as e:
        raise ConfigError(f"cannot read RViz config: {e}", source=str(p)) from None
    return parse_rviz(text, str(p))
