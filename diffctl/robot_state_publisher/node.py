"""The robot_state_publisher node: its parameters as ROS 2 Jazzy's declares them, then three callbacks.

As robot_state_publisher (C++, rclcpp): `robot_description` (string), `publish_frequency` (double, 20.0, checked
to lie in [0, 1000] at start and on every set), `frame_prefix` (string) and `ignore_timestamp` (bool) are declared
without descriptors; the description is republished latched on `robot_description`, fixed joints go once to
`/tf_static`, and every `joint_states` message becomes `/tf` for the moving joints it names, stamped with the
message's stamp (zero → now) and at most `publish_frequency` times a second per joint unless `ignore_timestamp`.
Setting `robot_description` at run time re-reads the model and republishes the fixed transforms.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from diffctl.client.interfaces import cls
from diffctl.description.model import Model
from diffctl.description.pose import Pose
from diffctl.description.robot_files import parse_description, read_description_text
from diffctl.errors import DiffctlError, ParameterError
from diffctl.robot_state_publisher.kinematics import KinematicTree, Segment

NODE_NAME = "robot_state_publisher"


def load_description(text: str, base_dir: Path | None = None) -> Model:
    # TF needs no meshes, and a description may name files of another machine: do not check them. A URDF keeps
    # every link and joint as written (no Gazebo lumping), so TF has each frame ROS's robot_state_publisher gives.
    return parse_description(text, source="robot_description", base_dir=base_dir, simulation=False,
                             check_files=False)


def frequency_refusal(hz: float) -> str | None:
    return None if 0.0 <= hz <= 1000.0 else "publish_frequency must be between 0.0 and 1000.0"


class TfPublisher:
    """The transforms of one model: fixed ones once, moving ones per joint_states message (pure, no I/O)."""

    def __init__(self, model: Model, frame_prefix: str, warn: Any) -> None:
        self.model = model
        self.tree = KinematicTree.from_model(model)
        self.moving = self.tree.moving()
        self.frame_prefix = frame_prefix
        self._warn = warn
        self._warned: set[str] = set()
        self._last_ns: dict[str, int] = {}
        # the node's /tf messages by the moving joints they carry, refilled per sample (`moved_message`)
        self._reused: dict[tuple[str, ...], Any] = {}

    def _frame(self, link: str) -> str:
        return link if link == "world" else self.frame_prefix + link

    def fixed(self, stamp_ns: int) -> list[Any]:
        return [transform_msg(self._frame(s.parent), self._frame(s.child), s.origin, stamp_ns)
                for s in self.tree.fixed()]

    def _warn_once(self, key: str, text: str) -> None:
        if key not in self._warned:
            self._warned.add(key)
            self._warn(text)

    def moved(self, msg: Any, now_ns: int, interval_ns: int, ignore_timestamp: bool) -> list[Any]:
        """The transforms a joint_states message makes, [] when it is rate limited or names no moving joint."""
        return [transform_msg(self._frame(seg.parent), self._frame(seg.child), pose, stamp_ns)
                for seg, pose, stamp_ns in self._poses(msg, now_ns, interval_ns, ignore_timestamp)]

    def moved_message(self, msg: Any, now_ns: int, interval_ns: int, ignore_timestamp: bool) -> Any | None:
        """`moved` as one tf2_msgs/TFMessage, None when there is nothing to send. The message (and its transforms)
        is this publisher's own, filled again by the next call: publish it before then (publishing serializes).
        At rtf 0 a car's joint_states come hundreds of times a second, and building fresh messages was a sixth
        of the node's time."""
        poses = self._poses(msg, now_ns, interval_ns, ignore_timestamp)
        if not poses:
            return None
        key = tuple(seg.child for seg, _, _ in poses)
        out = self._reused.get(key)
        if out is None:
            out = cls("tf2_msgs/msg/TFMessage")(transforms=[
                transform_msg(self._frame(seg.parent), self._frame(seg.child), pose, stamp_ns)
                for seg, pose, stamp_ns in poses])
            self._reused[key] = out
            return out
        for t, (_, pose, stamp_ns) in zip(out.transforms, poses, strict=True):
            _fill(t, pose, stamp_ns)
        return out

    def _poses(
        self, msg: Any, now_ns: int, interval_ns: int, ignore_timestamp: bool
    ) -> list[tuple[Segment, Pose, int]]:
        names, positions = list(msg.name), list(msg.position)
        if len(names) != len(positions):
            self._warn_once("sizes", f"joint_states with {len(names)} names but {len(positions)} positions: ignored")
            return []
        stamp = msg.header.stamp
        stamp_ns = int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec) or now_ns
        moving = self.moving
        known = [(n, float(q)) for n, q in zip(names, positions, strict=True) if n in moving]
        if not known:
            return []
        if not ignore_timestamp and interval_ns:
            never = -(2**62)
            seen = [self._last_ns.get(n, never) for n, _ in known]
            if stamp_ns < max(seen):
                self._last_ns.clear()  # time went backwards (a sim reset): start afresh, as rclcpp's RSP does
            elif stamp_ns < min(seen) + interval_ns:
                return []
        out = []
        for name, q in known:
            if not math.isfinite(q):
                self._warn_once(name, f"joint {name!r} position is {q}: not published")
                continue
            seg: Segment = self.moving[name]
            out.append((seg, seg.transform(q), stamp_ns))
            self._last_ns[name] = stamp_ns
        return out


def transform_msg(parent: str, child: str, pose: Pose, stamp_ns: int) -> Any:
    # Filled in place: keyword arguments would build every nested default first and then replace it (twice the
    # messages per transform, on every joint_states sample).
    msg = cls("geometry_msgs/msg/TransformStamped")()
    msg.header.frame_id = parent
    msg.child_frame_id = child
    _fill(msg, pose, stamp_ns)
    return msg


def _fill(msg: Any, pose: Pose, stamp_ns: int) -> None:
    """A TransformStamped's stamp and transform, set in place."""
    stamp = msg.header.stamp
    stamp.sec, stamp.nanosec = divmod(stamp_ns, 1_000_000_000)
    t, r = msg.transform.translation, msg.transform.rotation
    x, y, z = pose.xyz
    qx, qy, qz, qw = pose.quat
    t.x, t.y, t.z = float(x), float(y), float(z)
    r.x, r.y, r.z, r.w = float(qx), float(qy), float(qz), float(qw)


def description_text(description_file: Path | None, override: Any) -> tuple[str, Path | None]:
    """The description to publish (the file given on the command line wins) and the folder its paths are
    relative to; ParameterError when there is none."""
    if description_file is not None:
        return read_description_text(description_file), description_file.resolve().parent
    if not isinstance(override, str) or not override.strip():
        raise ParameterError("robot_description parameter must not be empty", field="robot_description",
                             hint='pass --description FILE, or -p robot_description:="$(cat FILE)"')
    return override, None


def make_node(description: str, model: Model, base_dir: Path | None, overrides: list[Any]) -> Any:
    """The node, its parameters declared as upstream's, publishing until destroyed."""
    from diffctl.client.node import Node
    from diffctl.client.parameter import Parameter
    from diffctl.client.qos import DurabilityPolicy, QoSPolicyKind, QoSProfile, ReliabilityPolicy
    from diffctl.client.qos_overriding_options import QoSOverridingOptions

    joint_state, string, tf_message, result = map(cls, (
        "sensor_msgs/msg/JointState", "std_msgs/msg/String", "tf2_msgs/msg/TFMessage",
        "rcl_interfaces/msg/SetParametersResult"))
    node = Node(NODE_NAME, client_library="rclcpp",
                parameter_overrides=[Parameter("robot_description", value=description), *overrides])
    node.declare_parameter("robot_description", "")
    hz = node.declare_parameter("publish_frequency", 20.0).value
    if frequency_refusal(hz):
        raise ParameterError(f"publish_frequency must be between 0 and 1000, got {hz}", field="publish_frequency")
    node.declare_parameter("frame_prefix", "")
    node.declare_parameter("ignore_timestamp", False)
    log = node.get_logger()
    state = TfPublisher(model, node.get_parameter("frame_prefix").value, log.warning)
    # tf2_ros' broadcasters: /tf keep_last 100, /tf_static keep_last 1 transient local, their QoS overridable
    tf_overrides = QoSOverridingOptions([QoSPolicyKind.DEPTH, QoSPolicyKind.DURABILITY, QoSPolicyKind.HISTORY,
                                         QoSPolicyKind.RELIABILITY])
    static_overrides = QoSOverridingOptions([QoSPolicyKind.DEPTH, QoSPolicyKind.HISTORY, QoSPolicyKind.RELIABILITY])
    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    pub_tf = node.create_publisher(tf_message, "/tf", 100, qos_overriding_options=tf_overrides)
    pub_static = node.create_publisher(tf_message, "/tf_static", latched, qos_overriding_options=static_overrides)
    pub_description = node.create_publisher(string, "robot_description", latched)

    def now_ns() -> int:
        return node.get_clock().now().nanoseconds

    def setup(text: str, model: Model) -> None:
        state.__init__(model, node.get_parameter("frame_prefix").value, log.warning)
        pub_description.publish(string(data=text))
        pub_static.publish(tf_message(transforms=state.fixed(now_ns())))
        log.info(f"model {model.name!r}: root {state.tree.root!r}, {len(list(state.tree.fixed()))} fixed and "
                 f"{len(state.moving)} moving joints")
        if state.tree.unsupported():
            log.warning(f"joints without a single position are not published: {', '.join(state.tree.unsupported())}")

    # publish_frequency and ignore_timestamp as of the last set, read once per change rather than per sample
    limits = {"interval_ns": 0, "ignore_timestamp": False}

    def read_limits() -> None:
        hz = node.get_parameter("publish_frequency").value
        limits["interval_ns"] = int(1e9 / hz) if hz > 0 else 0
        limits["ignore_timestamp"] = node.get_parameter("ignore_timestamp").value

    def on_joint_states(msg: Any) -> None:
        out = state.moved_message(msg, now_ns(), limits["interval_ns"], limits["ignore_timestamp"])
        if out is not None:
            pub_tf.publish(out)

    parsed: dict[str, Model] = {}

    def check(params: list[Any]) -> Any:
        for p in params:
            if p.name == "robot_description":
                if not p.value:
                    return result(successful=False, reason="Empty URDF is not allowed")
                try:
                    parsed[p.value] = load_description(p.value, base_dir)
                except DiffctlError as e:
                    log.warning(str(e))
                    return result(successful=False, reason=str(e))
            elif p.name == "publish_frequency" and frequency_refusal(p.value):
                return result(successful=False, reason=frequency_refusal(p.value))
        return result(successful=True)

    def changed(params: list[Any]) -> None:
        for p in params:
            if p.name == "robot_description":
                setup(p.value, parsed.pop(p.value))
        read_limits()

    sensor_data = QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT)  # rclcpp::SensorDataQoS
    node.create_subscription(joint_state, "joint_states", on_joint_states, sensor_data,
                             qos_overriding_options=QoSOverridingOptions.with_default_policies())
    setup(description, model)
    read_limits()
    node.add_on_set_parameters_callback(check)
    node.add_post_set_parameters_callback(changed)
    return node


def run(description_file: Path | None, overrides: list[Any]) -> int:
    """Read and check the description before anything touches the bus, then run the node."""
    from diffctl import ros_args
    from diffctl.client import component

    ra = ros_args.current(NODE_NAME)
    given = next((p.value for p in overrides if p.name == "robot_description"), ra.params.get("robot_description"))
    text, base_dir = description_text(description_file, given)
    model = load_description(text, base_dir)
    return component.run(lambda: make_node(text, model, base_dir, overrides))
