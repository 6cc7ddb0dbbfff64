"""The two tf2_ros programs on the bus: static_transform_publisher (one latched /tf_static transform, as
tf2_ros::StaticTransformBroadcasterNode) and tf2_echo (a listener on /tf and /tf_static printing a lookup at
its rate). Exit codes and messages as the C++ programs'."""

from __future__ import annotations

import random
import signal
import sys
import threading
import time
from typing import Any

from diffctl.tf2_tools.args import STATIC_USAGE, ArgsError, EchoUsage, parse_echo, parse_static
from diffctl.tf2_tools.echo_format import echo_block

TF_TYPE = "tf2_msgs/msg/TFMessage"
_NAME_CHARS = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"


def _rcutils_log(level: str, text: str) -> None:
    # RCUTILS_LOG_* without a node: the logger name is empty
    sys.stderr.write(f"[{level}] [{time.time_ns() / 1e9:.6f}] []: {text}\n")
    sys.stderr.flush()


def unique_node_name() -> str:
    """static_transform_publisher_ and 16 random letters or digits, as the node names itself."""
    return "static_transform_publisher_" + "".join(random.choice(_NAME_CHARS) for _ in range(16))


def _stop_on_signals() -> threading.Event:
    stop = threading.Event()
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: stop.set())
    return stop


def static_transform_publisher(argv: list[str]) -> int:
    """Publish one static transform on /tf_static until stopped; 1 with the usage on bad arguments."""
    try:
        st = parse_static(argv, warn=lambda text: _rcutils_log("WARN", text))
    except ArgsError as e:
        _rcutils_log("ERROR", f"error parsing command line arguments: {e}")
        print(STATIC_USAGE, flush=True)
        return 1
    if st.help:
        print(STATIC_USAGE, flush=True)
        return 0
    from diffctl.bus import Node, close_session
    from diffctl.bus.parameters import ParameterDescriptor

    # The program's values are the node's parameter overrides: they win over --ros-args files and -p.
    values = {"translation.x": st.translation[0], "translation.y": st.translation[1],
              "translation.z": st.translation[2], "rotation.x": st.rotation[0], "rotation.y": st.rotation[1],
              "rotation.z": st.rotation[2], "rotation.w": st.rotation[3], "frame_id": st.frame_id,
              "child_frame_id": st.child_frame_id}
    stop = _stop_on_signals()
    node = Node.from_ros_args(unique_node_name(), params=values)
    try:
        ro = ParameterDescriptor(read_only=True)
        defaults = {"translation.x": 0.0, "translation.y": 0.0, "translation.z": 0.0, "rotation.x": 0.0,
                    "rotation.y": 0.0, "rotation.z": 0.0, "rotation.w": 1.0, "frame_id": "/frame",
                    "child_frame_id": "/child"}
        p = {name: node.declare_parameter(name, default, ro) for name, default in defaults.items()}
        if p["frame_id"] == p["child_frame_id"]:
            node.log.error(f"cannot publish static transform from '{p['frame_id']}' to '{p['child_frame_id']}', "
                           "exiting")
            return 1
        t_ns = node.clock.now_ns()
        pub = node.create_publisher("/tf_static", TF_TYPE, latched=True, depth=1)
        pub.publish({"transforms": [{
            "header": {"stamp": {"sec": t_ns // 1_000_000_000, "nanosec": t_ns % 1_000_000_000},
                       "frame_id": p["frame_id"]},
            "child_frame_id": p["child_frame_id"],
            "transform": {
                "translation": {"x": p["translation.x"], "y": p["translation.y"], "z": p["translation.z"]},
                "rotation": {"x": p["rotation.x"], "y": p["rotation.y"], "z": p["rotation.z"],
                             "w": p["rotation.w"]},
            },
        }]})
        node.log.info(
            "Spinning until stopped - publishing transform\n"
            f"translation: ('{p['translation.x']:f}', '{p['translation.y']:f}', '{p['translation.z']:f}')\n"
            f"rotation: ('{p['rotation.x']:f}', '{p['rotation.y']:f}', '{p['rotation.z']:f}', "
            f"'{p['rotation.w']:f}')\nfrom '{p['frame_id']}' to '{p['child_frame_id']}'"
        )
        while not stop.wait(0.25) and not node.shutting_down:
            pass
        return 0
    finally:
        node.close()
        close_session()


class _Listener:
    """tf2_ros::TransformListener's two subscriptions feeding a BufferCore."""

    def __init__(self, node: Any) -> None:
        from diffctl.tf2.buffer_core import BufferCore

        self.core = BufferCore()
        node.create_subscription("/tf", TF_TYPE, lambda m: self._on(m, False), depth=100)
        node.create_subscription("/tf_static", TF_TYPE, lambda m: self._on(m, True), latched=True, depth=100)

    def _on(self, msg: Any, static: bool) -> None:
        for t in msg.transforms:
            tr, rot = t.transform.translation, t.transform.rotation
            stamp = int(t.header.stamp.sec) * 1_000_000_000 + int(t.header.stamp.nanosec)
            self.core.set_transform(t.header.frame_id, t.child_frame_id, stamp, (tr.x, tr.y, tr.z),
                                    (rot.x, rot.y, rot.z, rot.w), "Authority undetectable", static)


def tf2_echo(argv: list[str]) -> int:
    """Print the transform from source_frame to target_frame at the rate given (1 Hz), until stopped."""
    try:
        a = parse_echo(argv)
    except EchoUsage as e:
        (sys.stdout if e.code == 1 else sys.stderr).write(str(e) + ("" if e.code == 1 else "\n"))
        return e.code
    from diffctl.bus import Node, close_session
    from diffctl.tf2.exceptions import TransformException

    stop = _stop_on_signals()
    node = Node.from_ros_args("tf2_echo")
    period_s = 1.0 / a.rate_hz if a.rate_hz > 0 else 1.0
    try:
        listener = _Listener(node)
        while not stop.is_set() and not node.shutting_down:
            ok, why = listener.core.can_transform(a.source_frame, a.target_frame, 0)
            if ok:
                break
            node.log.throttled("waiting", f"Waiting for transform {a.source_frame} ->  {a.target_frame}: {why}",
                               1.0, level="INFO")
            stop.wait(period_s)
        while not stop.is_set() and not node.shutting_down:
            try:
                stamp, t, q = listener.core.lookup_transform(a.source_frame, a.target_frame, 0)
                sys.stdout.write(echo_block(stamp // 1_000_000_000, stamp % 1_000_000_000, t, q))
            except TransformException as ex:
                sys.stdout.write(f"Failure at {node.clock.now_ns() / 1e9:.3f}\nException thrown:{ex}\n"
                                 f"The current list of frames is:\n{listener.core.all_frames_as_string()}\n")
            sys.stdout.flush()
            stop.wait(period_s)
        return 0
    finally:
        node.close()
        close_session()
