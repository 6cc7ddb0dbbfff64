"""The robot_state_publisher node: parameters, then three callbacks' worth of publishing.

As ROS 2 Jazzy's robot_state_publisher: `robot_description` is republished latched on `robot_description`,
fixed joints go once to `/tf_static` (latched), and every `joint_states` message becomes `/tf` for the
moving joints it names, stamped with the message's stamp (zero → now) and at most `publish_frequency` times
a second per joint unless `ignore_timestamp`. Frames are link names with `frame_prefix` in front.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from diffctl.description.model import Model
from diffctl.description.pose import Pose
from diffctl.description.robot_files import parse_description, read_description_text
from diffctl.errors import ParameterError
from diffctl.robot_state_publisher.kinematics import KinematicTree, Segment

NODE_NAME = "robot_state_publisher"


def _as_bool(name: str, value: Any) -> bool:
    if isinstance(value, bool):
        return value
    if isinstance(value, str) and value.strip().lower() in ("true", "false"):
        return value.strip().lower() == "true"
    raise ParameterError(f"parameter {name!r} must be true or false, got {value!r}", field=name)


@dataclass(frozen=True)
class RspParams:
    robot_description: str
    publish_frequency_hz: float = 20.0
    frame_prefix: str = ""
    ignore_timestamp: bool = False
    use_sim_time: bool = False

    @staticmethod
    def from_dict(params: dict[str, Any]) -> RspParams:
        """Validated parameters; unknown names are ignored, as ROS nodes do for undeclared parameters."""
        desc = params.get("robot_description")
        if not isinstance(desc, str) or not desc.strip():
            raise ParameterError(
                "parameter 'robot_description' is not set"
                if desc in (None, "")
                else f"parameter 'robot_description' must be the SDF text, got {type(desc).__name__}",
                field="robot_description",
                hint='pass --description FILE, or -p robot_description:="$(cat FILE)"',
            )
        freq = params.get("publish_frequency", 20.0)
        if isinstance(freq, bool) or not isinstance(freq, int | float) or not 0.0 <= freq <= 1000.0:
            raise ParameterError(
                f"parameter 'publish_frequency' must be a number in [0, 1000] Hz, got {freq!r}",
                field="publish_frequency",
            )
        prefix = params.get("frame_prefix", "")
        if not isinstance(prefix, str):
            raise ParameterError(f"parameter 'frame_prefix' must be a string, got {prefix!r}", field="frame_prefix")
        return RspParams(
            robot_description=desc,
            publish_frequency_hz=float(freq),
            frame_prefix=prefix,
            ignore_timestamp=_as_bool("ignore_timestamp", params.get("ignore_timestamp", False)),
            use_sim_time=_as_bool("use_sim_time", params.get("use_sim_time", False)),
        )


def load_description(params: RspParams, base_dir: Path | None = None) -> Model:
    # TF needs no meshes, and a description may name files of another machine: do not check them. A URDF keeps
    # every link and joint as written (no Gazebo lumping), so TF has each frame ROS's robot_state_publisher gives.
    return parse_description(
        params.robot_description, source="robot_description", base_dir=base_dir, simulation=False, check_files=False
    )


def _classes(*typenames: str) -> tuple[Any, ...]:
    from diffctl.interfaces import types

    return tuple(types.get_class(t) for t in typenames)


def transform_msg(parent: str, child: str, pose: Pose, stamp_ns: int) -> Any:
    """geometry_msgs/TransformStamped built from the message classes: the per-joint_states path, where the
    checked dict conversion (`types.new`) cost ~100 µs a transform."""
    ts, header, time_, transform, vector3, quaternion = _classes(
        "geometry_msgs/msg/TransformStamped", "std_msgs/msg/Header", "builtin_interfaces/msg/Time",
        "geometry_msgs/msg/Transform", "geometry_msgs/msg/Vector3", "geometry_msgs/msg/Quaternion")
    x, y, z = pose.xyz
    qx, qy, qz, qw = pose.quat
    return ts(
        header=header(stamp=time_(sec=stamp_ns // 1_000_000_000, nanosec=stamp_ns % 1_000_000_000), frame_id=parent),
        child_frame_id=child,
        transform=transform(translation=vector3(x=float(x), y=float(y), z=float(z)),
                            rotation=quaternion(x=float(qx), y=float(qy), z=float(qz), w=float(qw))),
    )


def transform_dict(parent: str, child: str, pose: Pose, stamp_ns: int) -> dict[str, Any]:
    x, y, z = pose.xyz
    qx, qy, qz, qw = pose.quat
    return {
        "header": {
            "stamp": {"sec": stamp_ns // 1_000_000_000, "nanosec": stamp_ns % 1_000_000_000},
            "frame_id": parent,
        },
        "child_frame_id": child,
        "transform": {"translation": {"x": x, "y": y, "z": z}, "rotation": {"x": qx, "y": qy, "z": qz, "w": qw}},
    }


class RobotStatePublisher:
    """Publishes the description and TF of one model on `node` (a diffctl.bus.Node)."""

    def __init__(self, node: Any, params: RspParams, model: Model) -> None:
        self.node = node
        self.params = params
        self.tree = KinematicTree.from_model(model)
        self.moving = self.tree.moving()
        self._interval_ns = int(1e9 / params.publish_frequency_hz) if params.publish_frequency_hz > 0 else 0
        self._last_ns: dict[str, int] = {}
        self._warned: set[str] = set()
        self.pub_description = node.create_publisher("robot_description", "std_msgs/msg/String", latched=True)
        self.pub_static = node.create_publisher("/tf_static", "tf2_msgs/msg/TFMessage", latched=True)
        self.pub_tf = node.create_publisher("/tf", "tf2_msgs/msg/TFMessage", depth=100)
        (self._tf_message,) = _classes("tf2_msgs/msg/TFMessage")
        node.create_subscription("joint_states", "sensor_msgs/msg/JointState", self.on_joint_states)
        self.pub_description.publish({"data": params.robot_description})
        fixed = list(self.tree.fixed())
        self.pub_static.publish({"transforms": [self._tf(s, s.origin, node.now_ns()) for s in fixed]})
        node.log.info(
            f"model {model.name!r}: root {self.tree.root!r}, {len(fixed)} fixed and {len(self.moving)} moving joints"
        )
        if self.tree.unsupported():
            node.log.warn(f"joints without a single position are not published: {', '.join(self.tree.unsupported())}")

    def _frame(self, link: str) -> str:
        return link if link == "world" else self.params.frame_prefix + link

    def _tf(self, seg: Segment, pose: Pose, stamp_ns: int) -> dict[str, Any]:
        return transform_dict(self._frame(seg.parent), self._frame(seg.child), pose, stamp_ns)

    def _warn_once(self, key: str, text: str) -> None:
        if key not in self._warned:
            self._warned.add(key)
            self.node.log.warn(text)

    def on_joint_states(self, msg: Any) -> None:
        names, positions = list(msg.name), list(msg.position)
        if len(names) != len(positions):
            self._warn_once("sizes", f"joint_states with {len(names)} names but {len(positions)} positions: ignored")
            return
        stamp_ns = int(msg.header.stamp.sec) * 1_000_000_000 + int(msg.header.stamp.nanosec) or self.node.now_ns()
        known = [(n, float(q)) for n, q in zip(names, positions, strict=True) if n in self.moving]
        if not known:
            return
        if not self.params.ignore_timestamp and self._interval_ns:
            last = min(self._last_ns.get(n, -(2**62)) for n, _ in known)
            if stamp_ns < max(self._last_ns.get(n, -(2**62)) for n, _ in known):
                self._last_ns.clear()  # time went backwards (a sim reset): start afresh, as rclcpp's RSP does
            elif stamp_ns < last + self._interval_ns:
                return
        transforms = []
        for name, q in known:
            if not math.isfinite(q):
                self._warn_once(name, f"joint {name!r} position is {q}: not published")
                continue
            seg = self.moving[name]
            transforms.append(transform_msg(self._frame(seg.parent), self._frame(seg.child), seg.transform(q),
                                            stamp_ns))
            self._last_ns[name] = stamp_ns
        if transforms:
            self.pub_tf.publish(self._tf_message(transforms=transforms))


def run(params: dict[str, Any], *, description_file: Path | None = None) -> None:
    """Validate everything, then open the node and publish until SIGINT/SIGTERM."""
    from diffctl.bus import Node, close_session

    base_dir = None
    if description_file is not None:
        try:
            params = {**params, "robot_description": read_description_text(description_file)}
        except OSError as e:
            raise ParameterError(f"cannot read description: {e.strerror}", source=str(description_file)) from None
        base_dir = description_file.resolve().parent
    rsp_params = RspParams.from_dict(params)
    model = load_description(rsp_params, base_dir)  # before any bus traffic: a bad description starts nothing
    node = Node.from_ros_args(NODE_NAME, params={**params, "use_sim_time": rsp_params.use_sim_time})
    try:
        RobotStatePublisher(node, rsp_params, model)
        node.spin()
    finally:
        node.close()
        # Zenoh's callback threads are not daemons: close the session before the interpreter joins them.
        close_session()
