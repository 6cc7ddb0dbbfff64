"""interactive_marker_twist_server's marker_server on the client Node (node twist_server_node, every parameter
given declared): one interactive marker `<robot_name>_twist_marker` in `link_name` under the namespace
twist_server, with a move control per configured linear axis and a rotate control; each drag publishes a Twist
on `cmd_vel` (depth 1) and snaps the marker back to the robot."""

from __future__ import annotations

from typing import Any

from diffctl.errors import ConfigError
from diffctl.interactive_marker_twist_server.twist_from_pose import AXES, DEFAULT, Scales, twist
from diffctl.interactive_markers.server import InteractiveMarkerServer

NODE_NAME = "twist_server_node"
# the controls' orientations (w, x, y, z) and interaction modes (MOVE_AXIS 3, ROTATE_AXIS 5)
MOVE = {"x": (1.0, 1.0, 0.0, 0.0), "y": (1.0, 0.0, 0.0, 1.0), "z": (1.0, 0.0, 1.0, 0.0)}
ROTATE_Z = (1.0, 0.0, 1.0, 0.0)


def _group(node: Any, prefix: str) -> dict[str, float]:
    """rclcpp's get_parameters(prefix, map<string, double>): the doubles under `prefix.`."""
    out = {}
    for name, p in node.get_parameters_by_prefix(prefix).items():
        if not isinstance(p.value, float):
            raise ConfigError(f"parameter '{prefix}.{name}' has invalid type: expected [double] got "
                              f"[{type(p.value).__name__}] {p.value!r}", field=f"{prefix}.{name}")
        out[name] = p.value
    return out


def read(node: Any) -> tuple[str, str, Scales]:
    link = node.get_parameter("link_name").value if node.has_parameter("link_name") else "base_link"
    robot = node.get_parameter("robot_name").value if node.has_parameter("robot_name") else "robot"
    linear = _group(node, "linear_scale")
    scales = Scales(linear, _group(node, "max_positive_linear_velocity"),
                    _group(node, "max_negative_linear_velocity")) if linear else DEFAULT
    return str(link), str(robot), scales


def marker(link: str, robot: str, scales: Scales) -> Any:
    from diffctl.interfaces import get_interface as msg

    control_cls, quat = msg("visualization_msgs/msg/InteractiveMarkerControl"), msg("geometry_msgs/msg/Quaternion")
    m = msg("visualization_msgs/msg/InteractiveMarker")(name=f"{robot}_twist_marker",
                                                        description=f"twist controller for {robot}", scale=1.0)
    m.header.frame_id = link
    controls = [(f"move_{a}", MOVE[a], 3) for a in AXES if a in scales.linear] + [("rotate_z", ROTATE_Z, 5)]
    m.controls = [control_cls(name=name, orientation=quat(w=w, x=x, y=y, z=z), orientation_mode=1,
                              interaction_mode=mode) for name, (w, x, y, z), mode in controls]
    return m


def attach(node: Any) -> InteractiveMarkerServer:
    from diffctl.interfaces import get_interface as msg

    link, robot, scales = read(node)
    pub = node.create_publisher(msg("geometry_msgs/msg/Twist"), "cmd_vel", 1)
    server = InteractiveMarkerServer("twist_server", node)
    name = f"{robot}_twist_marker"
    twist_cls, vector, pose_cls = (msg(t) for t in ("geometry_msgs/msg/Twist", "geometry_msgs/msg/Vector3",
                                                    "geometry_msgs/msg/Pose"))

    def on_feedback(feedback: Any) -> None:
        p, q = feedback.pose.position, feedback.pose.orientation
        (lx, ly, lz), wz = twist(scales, (p.x, p.y, p.z), (q.x, q.y, q.z, q.w))
        pub.publish(twist_cls(linear=vector(x=lx, y=ly, z=lz), angular=vector(z=wz)))
        server.set_pose(name, pose_cls())  # back onto the robot
        server.apply_changes()

    server.insert(marker(link, robot, scales))
    server.set_callback(name, on_feedback)
    server.apply_changes()
    node.get_logger().info("[interactive_marker_twist_server] Initialized.")
    return server


def run() -> int:
    from diffctl.client import component
    from diffctl.client.node import Node

    def make() -> Any:
        node = Node(NODE_NAME, client_library="rclcpp", allow_undeclared_parameters=True,
                    automatically_declare_parameters_from_overrides=True)
        attach(node)
        return node

    return component.run(make)
